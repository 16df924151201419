//! Independent pieces of work, run in parallel with the `parallel` feature
//! (rayon), their results in order: the same whatever the number of threads.
//! The geometry's rows and beams go through it, and so do `monge-io`'s
//! chunked writers and its side-by-side files.

/// `f(0), f(1), …, f(n − 1)`, computed side by side where the `parallel`
/// feature is on (on this thread where there are no threads, as in
/// WebAssembly), returned in order. A panic in `f` is passed on.
///
/// ```
/// let squares = monge_core::tasks::map(1000, |k| k * k);
/// assert_eq!(squares, (0..1000).map(|k| k * k).collect::<Vec<_>>());
/// ```
pub fn map<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        (0..n).into_par_iter().map(f).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        (0..n).map(f).collect()
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn results_come_in_order() {
        assert_eq!(
            super::map(1000, |k| k * k),
            (0..1000).map(|k| k * k).collect::<Vec<_>>()
        );
    }
}
