//! The IGES reader (entity 128 surfaces).
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| monge_fuzz::iges(data));
