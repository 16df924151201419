//! `monge bench`: its JSON lines and its refusals.

use serde_json::Value;

use crate::common;
use common::{monge, refuses};

#[test]
fn bench_refuses_a_size_below_2() {
    // n = 1 was documented as valid, then failed on a straight guide.
    refuses(monge().args(["bench", "--sizes", "1"]), &["--sizes"], &[]);
}

#[test]
fn bench_prints_one_json_line_per_size() {
    let out = monge()
        .args(["bench", "--sizes", "10,12", "--runs", "3"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 2, "{text}");
    assert!(
        lines[0].starts_with(r#"{"faces":"10x10","median_ms":"#),
        "{}",
        lines[0]
    );
    for (line, faces) in lines.iter().zip(["10x10", "12x12"]) {
        let v: Value = serde_json::from_str(line).unwrap();
        assert_eq!(v["faces"], faces);
        assert_eq!(v["runs"], 3);
        assert!(v["median_ms"].as_f64().unwrap() > 0.0);
    }
}

#[test]
fn bench_all_prints_one_json_line_per_command_and_size() {
    let out = monge()
        // Two runs each: the second removes the first's output (a file, or
        // fabricate's directory) before it writes anew.
        .args(["bench", "--all", "--sizes", "4,6", "--runs", "2"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 2 * 9, "{text}");
    assert!(
        text.contains("\"command\":\"generate .ply binary\""),
        "{text}"
    );
    for (k, v) in lines.iter().enumerate() {
        let n: u32 = if k < 9 { 4 } else { 6 };
        assert_eq!(v["faces"], format!("{n}x{n}"));
        assert_eq!(v["runs"], 2);
        let n = f64::from(n);
        let wall = v["wall_ms"].as_f64().unwrap();
        assert!(wall > 0.0, "{v}");
        // ms per million faces is the wall time scaled by the face count (both
        // printed to 0.1: the wall time's rounding is scaled too).
        let (per, mfaces) = (v["ms_per_mface"].as_f64().unwrap(), n * n / 1e6);
        assert!((per - wall / mfaces).abs() <= 0.05 + 0.05 / mfaces, "{v}");
        assert!(v["peak_rss_mb"].as_f64().unwrap() > 1.0, "{v}");
        let bytes = v["bytes"].as_u64().unwrap();
        if v["command"] == "check .obj" {
            assert_eq!(bytes, 0);
            assert!(v["ratio_to_raw"].is_null());
        } else {
            assert!(
                bytes > 0 && v["ratio_to_raw"].as_f64().unwrap() > 0.0,
                "{v}"
            );
        }
    }
}
