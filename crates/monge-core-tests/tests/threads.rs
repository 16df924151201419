//! The generator gives the same mesh and report to the bit whatever the number
//! of threads (§2.2.3: the rows are independent chains; see `combescure`).
#![cfg(feature = "parallel")]

use monge_core::{generate, Design, GenerateError, GenerateOptions, Generated, GuideSpec};

use crate::common;
use common::{bits, design};

fn example(name: &str) -> Design {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// `design` with its B-spline or arc guides sampled `samples` times.
fn resampled(mut design: Design, samples: usize) -> Design {
    for g in [&mut design.guide_u, &mut design.guide_v] {
        match g {
            GuideSpec::BSpline { bspline, .. } => bspline.samples = samples,
            GuideSpec::Arc(a) => a.samples = samples,
            GuideSpec::Points { .. } | GuideSpec::Parabola(_) => {
                panic!("a B-spline or arc guide")
            }
        }
    }
    design
}

fn in_pool(threads: usize, design: &Design) -> Result<Generated, GenerateError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| generate(design, &GenerateOptions::default()))
}

/// The bits of the vertices and of the node axes.
fn grid_bits(g: &Generated) -> (Vec<[u64; 3]>, Vec<[u64; 3]>) {
    (bits(&g.grid.vertices), bits(&g.grid.normals))
}

#[test]
fn one_two_and_three_threads_give_the_same_bits() {
    let freeform = example("fig13-freeform.json");
    // Figure 14's guides (examples/fig14-family.toml) at θ = 100°: folded (§4.3).
    let quadratic = |p: [[f64; 3]; 3]| GuideSpec::bspline(2, p.to_vec(), 41);
    let folded = design(
        100.0,
        quadratic([[0.0, 0.0, 0.0], [5.0, 0.0, 0.0], [10.0, 0.0, 4.0]]),
        quadratic([[0.0, 0.0, 0.0], [0.0, 4.0, 0.0], [0.0, 8.0, 3.0]]),
    );
    let designs = [
        resampled(freeform, 301),
        resampled(example("fig12-dupin-theta30.json"), 203),
        resampled(folded, 150),
    ];
    for design in &designs {
        let one = in_pool(1, design).unwrap();
        for threads in [2, 3] {
            let g = in_pool(threads, design).unwrap();
            assert_eq!(grid_bits(&g), grid_bits(&one), "{threads} threads");
            assert_eq!(g.report, one.report, "{threads} threads");
        }
    }
    assert!(in_pool(1, &designs[2]).unwrap().report.folded_faces > 0);
}

#[test]
fn the_first_degenerate_face_does_not_depend_on_the_threads() {
    // The torus of degenerate.rs whose profile has a sample on the top circle, with
    // 401 rows: every row has a zero Gauss edge at column 18, in every task.
    let mut d = resampled(example("fig12-torus.json"), 401);
    let GuideSpec::Arc(profile) = &mut d.guide_v else {
        panic!("an arc guide_v");
    };
    (profile.angle_deg, profile.samples) = (150.0, 31);
    let answers = [1, 2, 3].map(|threads| match in_pool(threads, &d) {
        Err(GenerateError::Degenerate { face, sine, .. }) => (face, sine.to_bits()),
        other => panic!("{threads} threads: {:?}", other.map(|g| g.report)),
    });
    assert_eq!(answers[0].0, (0, 17));
    assert!(answers.iter().all(|a| *a == answers[0]), "{answers:?}");
}

/// `approximate` runs its starts in parallel: the design found is the same to the bit.
#[test]
fn approximate_finds_the_same_design_on_one_and_three_threads() {
    use monge_core::approximate::{approximate, ApproxOptions};
    let target: Vec<glam::DVec3> = (0..21 * 21)
        .map(|k| {
            let (x, y) = ((k % 21) as f64 * 0.5, (k / 21) as f64 * 0.5);
            glam::DVec3::new(x, y, 0.04 * x * x + 0.1 * y * y)
        })
        .collect();
    let options = ApproxOptions {
        faces: (8, 8),
        starts: 3,
        max_evaluations: 150,
        ..Default::default()
    };
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| approximate(&target, &options, &mut |_| {}).unwrap())
    };
    let (one, three) = (run(1), run(3));
    assert_eq!(one.design, three.design);
    assert_eq!(one.evaluations, three.evaluations);
    assert_eq!(one.starts, 3);
}
