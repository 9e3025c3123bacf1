//! Process resource use from getrusage(2): CPU time (the cost of single-threaded work on a
//! machine shared with other jobs, where wall time is not) and peak memory.

/// Peak resident set size of this process so far (bytes), from getrusage.
pub fn peak_rss_bytes() -> u64 {
    // SAFETY: getrusage writes into a zeroed rusage we own.
    let mut ru: libc_rusage::Rusage = unsafe { std::mem::zeroed() };
    let ok = unsafe { libc_rusage::getrusage(0, &mut ru) } == 0;
    if ok {
        ru.ru_maxrss as u64 * 1024 // Linux: kilobytes
    } else {
        0
    }
}

/// CPU time (user + system) of this process so far (seconds), from getrusage: the cost
/// of single-threaded work on a machine shared with other jobs, where wall time is not.
pub fn cpu_seconds() -> f64 {
    // SAFETY: getrusage writes into a zeroed rusage we own.
    let mut ru: libc_rusage::Rusage = unsafe { std::mem::zeroed() };
    if unsafe { libc_rusage::getrusage(0, &mut ru) } != 0 {
        return 0.0;
    }
    let t = |v: &libc_rusage::Timeval| v.tv_sec as f64 + 1e-6 * v.tv_usec as f64;
    t(&ru.ru_utime) + t(&ru.ru_stime)
}

/// Minimal getrusage binding (Linux x86_64/aarch64 layout), to avoid a libc dependency.
mod libc_rusage {
    #[repr(C)]
    pub struct Timeval {
        pub tv_sec: i64,
        pub tv_usec: i64,
    }
    #[repr(C)]
    pub struct Rusage {
        pub ru_utime: Timeval,
        pub ru_stime: Timeval,
        pub ru_maxrss: i64,
        pub rest: [i64; 13],
    }
    extern "C" {
        pub fn getrusage(who: i32, usage: *mut Rusage) -> i32;
    }
}
