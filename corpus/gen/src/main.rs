//! `swm-corpus [--out DIR]`: writes the standard mesh set as `DIR/NAME.obj`.

use std::path::PathBuf;
use std::process::ExitCode;

const USAGE: &str = "usage: swm-corpus [--out DIR]

Writes the generated test meshes (uv-sphere, icosphere, torus, double-torus,
fandisk-like, cube, plane-patch) as DIR/NAME.obj. DIR defaults to
corpus/generated and is created if missing.";

fn main() -> ExitCode {
    let mut out = PathBuf::from("corpus/generated");
    let mut args = std::env::args_os().skip(1);
    while let Some(arg) = args.next() {
        match arg.to_str() {
            Some("-h" | "--help") => {
                println!("{USAGE}");
                return ExitCode::SUCCESS;
            }
            Some("--out") => match args.next() {
                Some(dir) => out = dir.into(),
                None => return usage_error("--out needs a directory"),
            },
            Some(s) if s.starts_with("--out=") => out = s["--out=".len()..].into(),
            _ => return usage_error(&format!("unexpected argument {arg:?}")),
        }
    }
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("swm-corpus: cannot create {}: {e}", out.display());
        return ExitCode::FAILURE;
    }
    for (name, mesh) in swm_corpus::all() {
        let path = out.join(format!("{name}.obj"));
        if let Err(e) = swm_corpus::save_obj(&mesh, &path) {
            eprintln!("swm-corpus: cannot write {}: {e}", path.display());
            return ExitCode::FAILURE;
        }
        println!(
            "{}: {} vertices, {} triangles",
            path.display(),
            mesh.vertex_count(),
            mesh.face_count()
        );
    }
    ExitCode::SUCCESS
}

fn usage_error(msg: &str) -> ExitCode {
    eprintln!("swm-corpus: {msg}\n\n{USAGE}");
    ExitCode::from(2)
}
