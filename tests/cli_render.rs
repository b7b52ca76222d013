//! `swm render` (issue 23, the README's before/after picture): a mesh
//! or a `.swm` file becomes a well-formed SVG of its front faces, the
//! same bytes on every run; bad input is one line on stderr and a
//! non-zero exit, with no output left behind.

mod common;
use common::*;
use std::path::Path;

/// An icosphere written as OBJ into `dir`; its triangle count.
fn sphere(dir: &Path) -> (std::path::PathBuf, usize) {
    let mesh = swm_corpus::icosphere(1.0, 2);
    let path = dir.join("sphere.obj");
    swm::io::write_mesh(&path, &mesh).unwrap();
    (path, mesh.face_count())
}

/// Renders `input` to `output` with `extra` options; the SVG's text.
fn render(input: &Path, output: &Path, extra: &[&str]) -> String {
    let mut args = vec![
        "render",
        input.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    ok(&swm(&args));
    std::fs::read_to_string(output).expect("the SVG was written")
}

/// The value of `name="..."` in the SVG's opening tag.
fn attribute(svg: &str, name: &str) -> f64 {
    let tag = svg.lines().next().unwrap();
    tag.split(&format!(" {name}=\""))
        .nth(1)
        .and_then(|r| r.split('"').next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no {name} in {tag:?}"))
}

/// Checks the SVG's shape and returns its triangles: one `<path>` per
/// line, each a closed triangle of three points inside the canvas.
fn triangles(svg: &str) -> Vec<[[f64; 2]; 3]> {
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    assert!(
        svg.ends_with("</g>\n</svg>\n"),
        "{}",
        &svg[svg.len().saturating_sub(80)..]
    );
    let (w, h) = (attribute(svg, "width"), attribute(svg, "height"));
    let mut out = Vec::new();
    for line in svg.lines().filter(|l| l.starts_with("<path")) {
        let d = line
            .split(" d=\"M")
            .nth(1)
            .and_then(|r| r.strip_suffix("z\"/>"))
            .unwrap_or_else(|| panic!("not a closed path: {line}"));
        let n: Vec<f64> = d.split(' ').map(|x| x.parse().unwrap()).collect();
        assert_eq!(n.len(), 6, "{line}");
        for p in n.chunks(2) {
            assert!(
                (0.0..=w).contains(&p[0]) && (0.0..=h).contains(&p[1]),
                "{line}"
            );
        }
        out.push([[n[0], n[1]], [n[2], n[3]], [n[4], n[5]]]);
    }
    // Nothing else between the group's tags.
    let lines = svg.lines().count();
    assert_eq!(lines, out.len() + 4, "unexpected lines in the SVG");
    out
}

#[test]
fn a_sphere_draws_its_front_half_the_same_way_twice() {
    let dir = scratch("render-sphere");
    let (input, faces) = sphere(&dir);
    let a = render(&input, &dir.join("a.svg"), &[]);
    let b = render(&input, &dir.join("b.svg"), &[]);
    assert_eq!(a, b, "two runs gave different bytes");
    let drawn = triangles(&a);
    // An icosphere seen from any direction shows about half its faces;
    // none culled (or all) would be outside this.
    let share = drawn.len() as f64 / faces as f64;
    assert!((0.4..0.6).contains(&share), "{} of {faces}", drawn.len());
    // A sphere fits a square canvas of the default 512 px.
    assert_eq!(attribute(&a, "width"), 512.0);
    assert_eq!(attribute(&a, "height"), 512.0);
    // Front faces keep their counter-clockwise winding on the screen:
    // with SVG's y downwards, that is a negative signed area.
    for [p, q, r] in &drawn {
        let area = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
        assert!(area <= 0.0, "a back face was drawn: {p:?} {q:?} {r:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn view_and_size_change_the_picture() {
    let dir = scratch("render-view");
    let (input, _) = sphere(&dir);
    let front = render(&input, &dir.join("front.svg"), &[]);
    let back = render(
        &input,
        &dir.join("back.svg"),
        &["--view", "-1,-0.6,-1.4", "--size", "100"],
    );
    assert_ne!(triangles(&front), triangles(&back));
    assert_eq!(attribute(&back, "width"), 100.0);
    // A canvas too small to show anything is bad usage, refused by clap.
    let tiny = dir.join("tiny.svg");
    let (i, t) = (input.to_str().unwrap(), tiny.to_str().unwrap());
    assert_eq!(
        swm(&["render", i, "-o", t, "--size", "8"]).status.code(),
        Some(2)
    );
    assert!(!tiny.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_swm_file_renders() {
    let dir = scratch("render-swm");
    let (input, _) = sphere(&dir);
    let file = dir.join("sphere.swm");
    let (i, f) = (input.to_str().unwrap(), file.to_str().unwrap());
    ok(&swm(&["encode", i, "-o", f, "--mode", "lossless"]));
    let decoded = swm::decode(&std::fs::read(&file).unwrap(), &Default::default()).unwrap();
    let svg = render(&file, &dir.join("sphere.svg"), &[]);
    let drawn = triangles(&svg).len() as f64 / decoded.face_count() as f64;
    assert!((0.4..0.6).contains(&drawn), "{drawn}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs `args`, expects a failure of exit status `code`, with one line
/// on stderr that contains `needle`, and no file at `output`.
fn fails(args: &[&str], code: i32, needle: &str, output: &Path) {
    let out = swm(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(code), "{args:?}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
    assert!(stderr.starts_with("swm: error: "), "{stderr}");
    assert!(stderr.contains(needle), "{stderr} should name {needle}");
    assert!(!output.exists(), "{args:?} left {}", output.display());
}

#[test]
fn bad_input_is_one_line() {
    let dir = scratch("render-bad");
    let (input, _) = sphere(&dir);
    let svg = dir.join("out.svg");
    let (i, o) = (input.to_str().unwrap(), svg.to_str().unwrap());
    for view in ["0,0,0", "1,2", "x,y,z"] {
        fails(&["render", i, "-o", o, "--view", view], 2, "--view", &svg);
    }
    let missing = dir.join("missing.obj");
    let m = missing.to_str().unwrap();
    fails(&["render", m, "-o", o], 1, m, &svg);
    let mesh_out = dir.join("out.obj");
    let mo = mesh_out.to_str().unwrap();
    fails(&["render", i, "-o", mo], 2, ".svg", &mesh_out);
    // A .swm file that is not one.
    let bogus = dir.join("bogus.swm");
    std::fs::write(&bogus, b"not a swm file").unwrap();
    let b = bogus.to_str().unwrap();
    fails(&["render", b, "-o", o], 1, b, &svg);
    // Nothing to draw.
    let empty = dir.join("empty.obj");
    std::fs::write(&empty, "v 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
    let e = empty.to_str().unwrap();
    fails(&["render", e, "-o", o], 1, e, &svg);
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| is_temporary(n))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The README's before/after pictures are what its commands make today,
/// and the byte counts its prose gives are the files': a change to the
/// renderer or the encoder that alters them fails here until the
/// pictures are made again with those commands.
#[test]
fn the_readme_pictures_are_what_its_commands_make() {
    let Some(corpus) = shared_corpus() else {
        return;
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let block = readme
        .split("```sh\n")
        .filter_map(|b| b.split("```").next())
        .find(|b| b.contains("corpus/pictures/"))
        .expect("a sh block that makes corpus/pictures/");
    // Run where the outputs cannot replace the committed pictures, with
    // the corpus wherever this checkout finds it.
    let dir = scratch("render-readme");
    std::fs::create_dir_all(dir.join("corpus/pictures")).unwrap();
    let mut made = Vec::new();
    for line in block.lines().filter(|l| !l.trim().is_empty()) {
        let args: Vec<String> = line
            .strip_prefix("swm ")
            .unwrap_or_else(|| panic!("not a swm command: {line}"))
            .split_whitespace()
            .map(|a| match a.strip_prefix("../shared/corpus/") {
                Some(name) => corpus.join(name).to_str().unwrap().to_string(),
                None => a.to_string(),
            })
            .collect();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_swm"))
            .args(&args)
            .current_dir(&dir)
            .output()
            .unwrap();
        ok(&out);
        made.extend(args.iter().filter(|a| a.ends_with(".svg")).cloned());
    }
    assert_eq!(made.len(), 2, "{made:?}");
    let commas = |n: usize| {
        let s = n.to_string();
        let mut out = String::new();
        for (i, c) in s.chars().enumerate() {
            if i > 0 && (s.len() - i).is_multiple_of(3) {
                out.push(',');
            }
            out.push(c);
        }
        out
    };
    let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    for svg in &made {
        let fresh = std::fs::read(dir.join(svg)).unwrap();
        let committed = std::fs::read(root.join(svg)).unwrap();
        assert!(
            fresh == committed,
            "{svg} is not what the README's commands make"
        );
        let said = format!("{} bytes of SVG", commas(fresh.len()));
        assert!(flat.contains(&said), "README should say {said:?} of {svg}");
    }
    let swm_bytes = std::fs::metadata(dir.join("spot.swm")).unwrap().len() as usize;
    let said = format!("1 bit per vertex, {} bytes", commas(swm_bytes));
    assert!(flat.contains(&said), "README should say {said:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
