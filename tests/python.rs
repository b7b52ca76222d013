//! The Python front door (python/): rebuilds the `swm` extension module
//! into the project's virtual environment and runs its pytest suite, which
//! compares the binding with the `swm` binary built here (same `.swm`
//! bytes, same decoded meshes, same `info` and `distance` figures) and
//! runs the batch encoder on a two-worker Dask cluster over the shared
//! and the generated corpus.
//!
//! The environment is the one `SWM_PYENV` names, else `target/pyenv`
//! (made by `.ci/setup-python`), else `.venv` (made as README's "Use from
//! Python" says). Without it, or when pytest skips tests of its
//! own, the test reports a skip (`common::skip`) and passes, unless
//! `SWM_CI=1`, where a skip is a failure.

mod common;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tools/ has a parent")
        .to_path_buf()
}

/// Skips (or, under `SWM_CI=1`, fails) for want of `what`.
fn missing(what: &str) {
    let how = "run .ci/setup-python, or see README.md, \"Use from Python\"";
    common::skip(&format!("{what} not found ({how})"));
}

/// What pytest's report (`-rs`) says it skipped: its `SKIPPED [n] file:
/// reason` lines, and the suite's own `skipped: ...` warnings (a test
/// that runs with less than it could, such as the batch without the
/// shared corpus).
fn pytest_skips(report: &str) -> Vec<String> {
    report
        .lines()
        .filter_map(|line| {
            let line = line.trim();
            if let Some(rest) = line.strip_prefix("SKIPPED ") {
                Some(rest.to_string())
            } else {
                line.find("Warning: skipped: ")
                    .map(|at| line[at + "Warning: ".len()..].to_string())
            }
        })
        .collect()
}

/// The Python environment: `$SWM_PYENV`, else `target/pyenv` (what
/// `.ci/setup-python` makes), else `.venv` (what README's "Use from
/// Python" makes), else `target/pyenv` to name in the skip.
fn pyenv(root: &Path) -> PathBuf {
    if let Some(venv) = std::env::var_os("SWM_PYENV") {
        return PathBuf::from(venv);
    }
    ["target/pyenv", ".venv"]
        .iter()
        .map(|dir| root.join(dir))
        .find(|venv| venv.join("bin/python").is_file())
        .unwrap_or_else(|| root.join("target/pyenv"))
}

#[test]
fn pytest_suite() {
    let root = root();
    let venv = pyenv(&root);
    let python = venv.join("bin/python");
    if !python.is_file() {
        return missing(&format!("Python environment {}", venv.display()));
    }
    let has = |module: &str| {
        Command::new(&python)
            .args(["-c", &format!("import {module}")])
            .output()
            .is_ok_and(|o| o.status.success())
    };
    for module in ["maturin", "pytest", "numpy", "distributed"] {
        if !has(module) {
            return missing(&format!("Python module {module} in {}", venv.display()));
        }
    }

    // The extension is rebuilt against the library as it is now, so the
    // suite never tests a stale build (cargo makes this quick when
    // nothing changed).
    let build = Command::new(&python)
        .args(["-m", "maturin", "develop", "--release", "--quiet", "-m"])
        .arg(root.join("python/Cargo.toml"))
        .env("VIRTUAL_ENV", &venv)
        .output()
        .expect("run maturin");
    assert!(
        build.status.success(),
        "maturin develop failed:\n{}",
        String::from_utf8_lossy(&build.stderr)
    );

    let generated = common::scratch("python-generated");
    for (name, mesh) in swm_corpus::all() {
        swm_corpus::save_obj(&mesh, &generated.join(format!("{name}.obj")))
            .expect("write the generated corpus");
    }
    let mut pytest = Command::new(&python);
    pytest
        .args(["-m", "pytest", "-q", "-rs", "-p", "no:cacheprovider"])
        .arg(root.join("python/tests"))
        .current_dir(root.join("python"))
        .env("SWM_BIN", env!("CARGO_BIN_EXE_swm"))
        .env("SWM_GENERATED_CORPUS", &generated);
    if let Some(shared) = common::shared_corpus() {
        pytest.env("SWM_SHARED_CORPUS", shared);
    }
    let out = pytest.output().expect("run pytest");
    // The log shows pytest's report (skips included) whatever the outcome.
    println!("{}", String::from_utf8_lossy(&out.stdout));
    eprintln!("{}", String::from_utf8_lossy(&out.stderr));
    let _ = std::fs::remove_dir_all(&generated);
    assert!(
        out.status.success(),
        "the Python suite failed (report above)"
    );
    // pytest's own skips count as this test's: visible, and fatal in CI.
    let skips = pytest_skips(&String::from_utf8_lossy(&out.stdout));
    if !skips.is_empty() {
        common::skip(&format!(
            "pytest skipped {}: {}",
            skips.len(),
            skips.join("; ")
        ));
    }
}

#[test]
fn pytest_skips_are_found_in_its_report() {
    let report = "\
..s.
=============================== warnings summary ===============================
tests/test_batch.py::test_batch_over_both_corpora
  /x/tests/test_batch.py:71: UserWarning: skipped: ../shared/corpus not found; the batch runs over the generated corpus only
    warnings.warn(\"skipped: ../shared/corpus not found\")
=========================== short test summary info ============================
SKIPPED [1] tests/conftest.py:45: ../shared/corpus not found
SKIPPED [2] tests/test_batch.py:200: the dask command not found beside the Python interpreter
3 passed, 3 skipped, 1 warning in 2.50s
";
    assert_eq!(
        pytest_skips(report),
        [
            "skipped: ../shared/corpus not found; the batch runs over the generated corpus only",
            "[1] tests/conftest.py:45: ../shared/corpus not found",
            "[2] tests/test_batch.py:200: the dask command not found beside the Python interpreter",
        ]
    );
}
