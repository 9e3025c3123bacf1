//! Independent jobs on a few threads, results in the jobs' order: the mesh study's
//! meshes, the harmonic balance's element marches. Each worker takes the next job from
//! a shared counter, so jobs of unequal cost balance themselves.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Threads a parallel loop uses: the machine's available parallelism.
pub fn threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// `work` applied to every job on up to `threads` threads; results in the jobs' order.
pub fn in_parallel<J: Sync, T: Send>(
    jobs: &[J],
    threads: usize,
    work: impl Fn(&J) -> T + Sync,
) -> Vec<T> {
    in_parallel_with(jobs, threads, || (), |(), job| work(job))
}

/// [`in_parallel`] with scratch state of each worker, made by `init` once per thread
/// (e.g. FFT plans); one thread, or one job, runs on the calling thread.
pub fn in_parallel_with<J: Sync, T: Send, S>(
    jobs: &[J],
    threads: usize,
    init: impl Fn() -> S + Sync,
    work: impl Fn(&mut S, &J) -> T + Sync,
) -> Vec<T> {
    let threads = threads.clamp(1, jobs.len().max(1));
    if threads == 1 {
        let mut scratch = init();
        return jobs.iter().map(|job| work(&mut scratch, job)).collect();
    }
    let next = AtomicUsize::new(0);
    let done = Mutex::new(Vec::with_capacity(jobs.len()));
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| {
                let mut scratch = init();
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(job) = jobs.get(i) else { break };
                    let out = work(&mut scratch, job);
                    done.lock().expect("a worker panicked").push((i, out));
                }
            });
        }
    });
    let mut done = done.into_inner().expect("a worker panicked");
    done.sort_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, t)| t).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every job once, results in the jobs' order, for more, fewer and as many threads
    /// as jobs (and none).
    #[test]
    fn in_parallel_keeps_the_jobs_order() {
        let jobs: Vec<u64> = (0..37).collect();
        for threads in [0, 1, 2, 5, 37, 64] {
            let out = in_parallel(&jobs, threads, |&j| {
                std::thread::sleep(std::time::Duration::from_micros(37 - j));
                j * j
            });
            assert_eq!(
                out,
                jobs.iter().map(|j| j * j).collect::<Vec<_>>(),
                "{threads}"
            );
        }
        assert!(in_parallel(&[] as &[u64], 2, |&j| j).is_empty());
    }
}
