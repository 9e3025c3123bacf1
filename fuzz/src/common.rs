//! Shared by the fuzz targets: number generators that reach both garbage (raw bits: NaN,
//! ±∞, subnormals) and meaningful magnitudes (m·10^e over ±300 decades), the properties
//! checked on every call, and the stable stand-in for libFuzzer (`replay` feature).

#![allow(dead_code)]

use arbitrary::Arbitrary;

/// A double: raw bits, a scaled decimal, or one of the edge values.
#[derive(Debug, Clone, Copy, Arbitrary)]
pub enum F {
    Raw(u64),
    /// `mant`/16 · 10^`exp`, exp clamped to ±300.
    Scaled {
        mant: i16,
        exp: i16,
    },
    Edge(u8),
}

const EDGES: [f64; 16] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::MIN_POSITIVE,
    f64::MAX,
    f64::MIN,
    f64::EPSILON,
    5e-324,
    1e-300,
    1e300,
    0.5,
    2.0,
];

impl F {
    pub fn get(self) -> f64 {
        match self {
            F::Raw(bits) => f64::from_bits(bits),
            F::Scaled { mant, exp } => {
                f64::from(mant) / 16.0 * 10f64.powi(i32::from(exp.clamp(-300, 300)))
            }
            F::Edge(i) => EDGES[usize::from(i) % EDGES.len()],
        }
    }
}

/// A double near `base` (relative factor 10^(±8) or exactly base), or anything.
#[derive(Debug, Clone, Copy, Arbitrary)]
pub enum Near {
    Exact,
    /// base · (1 + k·2^-40)
    Ulps(i8),
    /// base · 10^(d/4)
    Decades(i8),
    Any(F),
}

impl Near {
    pub fn around(self, base: f64) -> f64 {
        match self {
            Near::Exact => base,
            Near::Ulps(k) => base * (1.0 + f64::from(k) * 2f64.powi(-40)),
            Near::Decades(d) => base * 10f64.powf(f64::from(d.clamp(-40, 40)) / 4.0),
            Near::Any(f) => f.get(),
        }
    }
}

/// Panics (a fuzz finding) when any value is not finite.
pub fn assert_finite(what: &str, values: &[f64]) {
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        panic!("{what}[{i}] = {} on JOINTLIN_OK", values[i]);
    }
}

/// Panics on JOINTLIN_ERR_PANIC (12) and on codes outside the documented 0..=12.
pub fn assert_status(what: &str, status: i32) {
    assert!(
        (0..12).contains(&status),
        "{what}: status {status}: {}",
        last_error()
    );
}

pub fn last_error() -> String {
    let mut buf = vec![0u8; 512];
    let n = unsafe { jointlin::ffi::error::jointlin_last_error(buf.as_mut_ptr().cast(), 512) };
    buf.truncate(n.min(511));
    String::from_utf8_lossy(&buf).into_owned()
}

/// The input as text for the harness's readers (None when not UTF-8), with the memory
/// limit fixed at 1 GiB: the readers' size checks take their own path and no input may
/// allocate beyond it.
pub fn text_input(data: &[u8]) -> Option<&str> {
    let text = std::str::from_utf8(data).ok()?;
    std::env::set_var("JOINTLIN_MAX_MEMORY", "1G");
    Some(text)
}

/// Panics (a fuzz finding) when an error's `line` lies beyond `text` (its lines + 1).
pub fn assert_line_within(text: &str, line: usize, error: &dyn std::fmt::Display) {
    let lines = text.lines().count().max(1) + 1;
    assert!(line <= lines, "line {line} of {lines}: {error}");
    let _ = error.to_string();
}

/// Stable stand-in for libFuzzer (`--features replay`): runs `target` on every file of the
/// directories/files given, then for `--seconds N` (default 10) on mutations of them (bit
/// flips, byte overwrites, truncation, splicing) and on random buffers; xorshift seeded by
/// `--seed S` (default 1). Not coverage-guided: a random search around the corpus.
pub fn replay_main(target: fn(&[u8])) {
    let mut seconds = 10.0;
    let mut seed: u64 = 1;
    let mut inputs: Vec<Vec<u8>> = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--seconds" => seconds = args.next().and_then(|s| s.parse().ok()).unwrap_or(10.0),
            "--seed" => seed = args.next().and_then(|s| s.parse().ok()).unwrap_or(1),
            path => {
                let p = std::path::Path::new(path);
                let files: Vec<std::path::PathBuf> = if p.is_dir() {
                    let mut v: Vec<_> = std::fs::read_dir(p)
                        .expect("corpus directory")
                        .map(|e| e.unwrap().path())
                        .collect();
                    v.sort();
                    v
                } else {
                    vec![p.to_path_buf()]
                };
                for f in files {
                    inputs.push(std::fs::read(&f).expect("corpus file"));
                }
            }
        }
    }
    let start = std::time::Instant::now();
    for input in &inputs {
        target(input);
    }
    let replayed = inputs.len();
    let mut state = seed.max(1);
    let mut rand = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let mut execs = 0u64;
    while start.elapsed().as_secs_f64() < seconds {
        let mut buf = if inputs.is_empty() || rand() % 4 == 0 {
            let n = (rand() % 2048) as usize;
            (0..n).map(|_| rand() as u8).collect()
        } else {
            inputs[(rand() % inputs.len() as u64) as usize].clone()
        };
        for _ in 0..1 + rand() % 8 {
            if buf.is_empty() {
                break;
            }
            let i = (rand() % buf.len() as u64) as usize;
            match rand() % 5 {
                0 => buf[i] ^= 1 << (rand() % 8),
                1 => buf[i] = rand() as u8,
                2 => buf.truncate(i),
                3 if !inputs.is_empty() => {
                    let other = &inputs[(rand() % inputs.len() as u64) as usize];
                    let j = (rand() % (other.len() as u64 + 1)) as usize;
                    buf.truncate(i);
                    buf.extend_from_slice(&other[j..]);
                }
                _ => {
                    let v = [0u8, 0xff, 0x7f, 0x80][(rand() % 4) as usize];
                    buf[i] = v;
                }
            }
        }
        target(&buf);
        execs += 1;
    }
    eprintln!(
        "replay: {replayed} corpus inputs, {execs} random/mutated inputs in {:.1} s, no failure",
        start.elapsed().as_secs_f64()
    );
}
