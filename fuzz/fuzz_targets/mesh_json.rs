//! The Json mesh reader, then `monge check`'s measurement of what it read.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| monge_fuzz::mesh(data, monge_io::MeshFormat::Json));
