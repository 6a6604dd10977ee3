//! The library's one worker pool (rayon): independent jobs on a given number of threads,
//! their results in the jobs' order, so that a study's result does not depend on the number
//! of threads.

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::iter::{IntoParallelRefIterator, ParallelIterator};

/// A pool of worker threads.
pub struct Pool(rayon::ThreadPool);

impl Pool {
    /// A pool of `threads` threads (0: one per core); the reason as a line when the system
    /// cannot start them.
    pub fn new(threads: usize) -> Result<Pool, String> {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map(Pool)
            .map_err(|e| format!("cannot start the thread pool: {e}"))
    }

    /// Its number of threads.
    pub fn threads(&self) -> usize {
        self.0.current_num_threads()
    }

    /// `work` on every job, `progress(done, total)` after each (from the worker threads);
    /// the results in the jobs' order.
    pub fn map<J: Sync, T: Send>(
        &self,
        jobs: &[J],
        work: impl Fn(&J) -> T + Sync,
        progress: Option<&(dyn Fn(usize, usize) + Sync)>,
    ) -> Vec<T> {
        let done = AtomicUsize::new(0);
        self.0.install(|| {
            jobs.par_iter()
                .map(|job| {
                    let r = work(job);
                    if let Some(p) = progress {
                        p(done.fetch_add(1, Ordering::Relaxed) + 1, jobs.len());
                    }
                    r
                })
                .collect()
        })
    }
}
