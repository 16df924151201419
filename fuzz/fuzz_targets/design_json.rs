//! Design files as Json: every kind (surface, developable, multi-patch, planes), parsed and generated.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| monge_fuzz::design(data, monge_io::DesignFormat::Json));
