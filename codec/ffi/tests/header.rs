//! `include/swm.h` is what cbindgen generates from `src/lib.rs` today:
//! a change to the C interface that forgot the header fails here.
//! `SWM_BLESS=1 cargo test -p swm-ffi --test header` rewrites it.

use std::path::Path;

#[test]
fn checked_in_header_is_current() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let bindings = cbindgen::Builder::new()
        .with_config(config)
        .with_src(dir.join("src/lib.rs"))
        .generate()
        .expect("cbindgen");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let path = dir.join("include/swm.h");
    if std::env::var_os("SWM_BLESS").is_some() {
        std::fs::write(&path, &generated).unwrap();
    }
    let checked_in = std::fs::read(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "include/swm.h is out of date; run SWM_BLESS=1 cargo test -p swm-ffi --test header"
    );
}
