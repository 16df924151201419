//! What reading a design costs in memory, counted by this test binary's own
//! allocator: about 6 times the file's size in JSON (it was 23), 90 in TOML (it
//! was 109).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

use monge_io::{parse_any_design, parse_design, AnyDesign, DesignFormat};

/// The system allocator, keeping the bytes in use and their peak.
struct Counting;

static IN_USE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let now = IN_USE.fetch_add(layout.size(), Relaxed) + layout.size();
        PEAK.fetch_max(now, Relaxed);
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        IN_USE.fetch_sub(layout.size(), Relaxed);
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The most bytes in use at once while `f` runs, beyond those in use before.
fn peak_of(f: impl FnOnce()) -> usize {
    let before = IN_USE.load(Relaxed);
    PEAK.store(before, Relaxed);
    f();
    PEAK.load(Relaxed) - before
}

/// A design whose guide_u has `n` short points (`[1,0,3]`: 8 bytes each, the
/// densest a design gets), in JSON or TOML.
fn dense(n: usize, format: DesignFormat) -> String {
    let points: Vec<String> = (0..n)
        .map(|k| format!("[{},0,{}]", k % 10, k % 7))
        .collect();
    let points = points.join(",");
    match format {
        DesignFormat::Json => format!(
            r#"{{"theta_deg": 30, "guide_u": {{"points": [{points}]}}, "guide_v": {{"arc": {{"center": [0, 0, -1], "start": [0, 0, 0], "normal": [-1, 0, 0], "angle_deg": 60, "samples": 3}}}}}}"#
        ),
        DesignFormat::Toml => format!(
            "theta_deg = 30\nguide_u.points = [{points}]\nguide_v.arc = {{ center = [0, 0, -1], \
             start = [0, 0, 0], normal = [-1, 0, 0], angle_deg = 60, samples = 3 }}\n"
        ),
    }
}

/// Measured: a 19 MB JSON design of 2.4 million such points peaked at 450 MB
/// (23×) in `monge info`, the TOML one at 2.1 GB (109×): the file's kind was
/// told from a tree of all its values, and TOML built two more trees to look
/// for `nan`. The parsed design itself holds 24 bytes a point (3× the text).
#[test]
fn reading_a_design_costs_a_few_times_its_size() {
    // TOML: the toml crate's own parse takes about 90 times the text (its tokens
    // and tree); it was twice that, with a second tree alive for `nan`.
    for (format, most) in [(DesignFormat::Json, 8.0), (DesignFormat::Toml, 100.0)] {
        let text = dense(100_000, format);
        let surface = |d: &monge_core::Design| d.guide_u.sample_count();
        let peaks = [
            peak_of(|| assert_eq!(surface(&parse_design(&text, format).unwrap()), 100_000)),
            peak_of(|| match parse_any_design(&text, format).unwrap() {
                AnyDesign::Surface(d) => assert_eq!(surface(&d), 100_000),
                AnyDesign::Developable(_) | AnyDesign::Trimmed(_) => panic!("a surface design"),
            }),
        ];
        for peak in peaks {
            let ratio = peak as f64 / text.len() as f64;
            eprintln!("{format:?}: {peak} bytes for {} ({ratio:.1}×)", text.len());
            assert!(
                ratio < most,
                "{format:?}: {peak} bytes for {} ({ratio:.1}×)",
                text.len()
            );
        }
    }
}
