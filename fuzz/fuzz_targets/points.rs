//! A target's points as STL and as a text file of points.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| monge_fuzz::points(data));
