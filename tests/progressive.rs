//! Issue 46, item 4 ("progressive by construction"): a displaced-
//! subdivision file cut at any level boundary is a valid file of the
//! coarser mesh. For a three-level file: every cut (`swm::cut_levels`)
//! decodes, to what `DecodeOptions::max_level` gives, with `T0 · 4^l`
//! triangles, its vertices the first ones of the whole file's bit for bit
//! (a level never moves an older vertex, and the whole file decodes to
//! the encoder's own reconstruction: `displaced/tests.rs`), and its
//! distance to the input falls level by level (the table this prints).

mod common;

use swm::{DecodeOptions, EncodeMode, EncodeOptions, MethodStats, SwingTarget, TriMesh};

/// A bumpy icosphere: smooth enough for subdivision to predict, with
/// detail for each level's scalars to add.
fn input() -> TriMesh {
    let mut m = swm_corpus::icosphere(1.0, 4);
    for p in &mut m.positions {
        let (x, y, z) = (p[0], p[1], p[2]);
        let r = 1.0 + 0.06 * (5.0 * x).sin() * (4.0 * y).cos() + 0.04 * (3.0 * z).sin();
        *p = [x * r, y * r, z * r];
    }
    m
}

/// The input coded by displaced subdivision at `bytes`: the file and its
/// level count.
fn displaced(mesh: &TriMesh, bytes: u64) -> (Vec<u8>, u8) {
    let options = EncodeOptions {
        mode: EncodeMode::Displaced {
            target: SwingTarget::Bytes(bytes),
            max_bytes: None,
        },
        ..EncodeOptions::default()
    };
    let encoded = swm::encode(mesh, &options).unwrap();
    let MethodStats::Displaced(s) = &encoded.stats.method else {
        panic!("not a displaced file");
    };
    (encoded.bytes, s.levels)
}

fn with_max_level(max_level: Option<u8>) -> DecodeOptions {
    DecodeOptions {
        max_level,
        ..DecodeOptions::default()
    }
}

fn bits(m: &TriMesh) -> Vec<u32> {
    m.positions.iter().flatten().map(|c| c.to_bits()).collect()
}

#[test]
fn every_level_cut_decodes_to_the_coarser_mesh_and_the_error_falls() {
    let mesh = input();
    // 12,000 bytes: the encoder makes three levels of this input (two
    // below about 9,500 bytes since levels carry bends).
    let (bytes, levels) = displaced(&mesh, 12000);
    assert_eq!(levels, 3);
    let limits = swm::Limits::default();
    let whole = swm::decode(&bytes, &DecodeOptions::default()).unwrap();
    let info = swm::inspect(&bytes, &limits).unwrap();
    assert_eq!(info.levels.len(), 3);
    let base_triangles = whole.triangles.len() >> 6;
    let mut last = f64::INFINITY;
    println!("level  triangles  file bytes  L2 / diagonal (1e-4)");
    for l in 0..=3u8 {
        let cut = swm::cut_levels(&bytes, usize::from(l), &limits).unwrap();
        let coarse = swm::decode(&cut, &DecodeOptions::default()).unwrap();
        coarse.validate().unwrap();
        // What `max_level` decodes from the whole file, bit for bit.
        let direct = swm::decode(&bytes, &with_max_level(Some(l))).unwrap();
        assert!(coarse.triangles == direct.triangles && bits(&coarse) == bits(&direct));
        assert_eq!(coarse.triangles.len(), base_triangles << (2 * l));
        // A level never moves an older vertex: the coarse mesh's vertices
        // are the whole file's first ones.
        let n = coarse.positions.len();
        assert_eq!(bits(&coarse), bits(&whole)[..3 * n], "level {l}");
        // The cut file is a file of `l` levels, each chunk as it was.
        let cut_info = swm::inspect(&cut, &limits).unwrap();
        assert_eq!(cut_info.levels, info.levels[..usize::from(l)]);
        let d = swm::metrics::distance(&mesh, &coarse, &Default::default())
            .unwrap()
            .l2_relative();
        println!(
            "{l:>5}  {:>9}  {:>10}  {:>8.2}",
            coarse.triangles.len(),
            cut.len(),
            d * 1e4
        );
        assert!(d < last, "level {l}: {d} after {last}");
        last = d;
    }
    // All levels: the file itself; above them, every level.
    assert_eq!(swm::cut_levels(&bytes, 3, &limits).unwrap(), bytes);
    assert_eq!(swm::cut_levels(&bytes, 9, &limits).unwrap(), bytes);
    let above = swm::decode(&bytes, &with_max_level(Some(200))).unwrap();
    assert!(above.triangles == whole.triangles && bits(&above) == bits(&whole));
}

/// Modes 0 and 1 have no levels: `max_level` changes nothing, and
/// `cut_levels` refuses them with a typed error.
#[test]
fn other_modes_ignore_max_level() {
    let mesh = swm_corpus::icosphere(1.0, 2);
    for mode in [
        EncodeMode::Lossless { qp: 12 },
        EncodeMode::Swing {
            target: SwingTarget::BitsPerVertex(4.0),
            angle_bits: None,
            max_bytes: None,
        },
    ] {
        let options = EncodeOptions {
            mode,
            ..EncodeOptions::default()
        };
        let bytes = swm::encode(&mesh, &options).unwrap().bytes;
        let all = swm::decode(&bytes, &DecodeOptions::default()).unwrap();
        let zero = swm::decode(&bytes, &with_max_level(Some(0))).unwrap();
        assert!(all == zero);
        assert!(swm::inspect(&bytes, &swm::Limits::default())
            .unwrap()
            .levels
            .is_empty());
        assert!(matches!(
            swm::cut_levels(&bytes, 0, &swm::Limits::default()),
            Err(swm::Error::Format(_))
        ));
    }
}

/// The command line: `swm info` lists the levels, `swm decode
/// --max-level N` writes the coarser mesh.
#[test]
fn the_cli_lists_levels_and_decodes_a_prefix() {
    let golden = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../format-spec/golden/displaced-v1.2.swm"
    );
    let text = common::ok(&common::swm(&["info", golden]));
    assert!(text.contains("levels                2"), "{text}");
    let v = common::json(&common::swm(&["info", golden, "--json"]));
    let chunks: Vec<u64> = v["level_bytes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b.as_u64().unwrap())
        .collect();
    // DISP's 508 bytes: two chunks and their one- or two-byte lengths.
    assert_eq!(chunks.len(), 2);
    assert!(
        (500..508).contains(&chunks.iter().sum::<u64>()),
        "{chunks:?}"
    );
    let dir = common::scratch("progressive_cli");
    for (level, triangles) in [(0, 564), (1, 2256), (2, 9024), (5, 9024)] {
        let out = dir.join(format!("level{level}.ply"));
        let max = level.to_string();
        let args = [
            "decode",
            golden,
            "-o",
            out.to_str().unwrap(),
            "--max-level",
            &max,
        ];
        common::ok(&common::swm(&args));
        let mesh = swm::io::read_mesh(&out).unwrap();
        assert_eq!(mesh.triangles.len(), triangles, "--max-level {level}");
    }
}

/// `swm info` of a displaced file says how it predicts and what its base
/// is, each level's step and bend, and prints no CLERS line (its
/// connectivity is its base's and the splits').
#[test]
fn the_cli_shows_a_displaced_files_prediction_steps_bends_and_base() {
    let golden = |name: &str| {
        format!(
            "{}/../format-spec/golden/{name}",
            env!("CARGO_MANIFEST_DIR")
        )
    };
    let bare = golden("displaced-bare-v1.2.swm");
    let v = common::json(&common::swm(&["info", &bare, "--json"]));
    assert_eq!(v["prediction"], "loop");
    assert_eq!(v["bare_base"], true);
    // format-spec/07-displaced.md, "Golden file": a bare BASE of 933 bytes.
    assert_eq!(v["base_bytes"], 933);
    let steps = v["steps"].as_array().unwrap();
    let bends = v["bends"].as_array().unwrap();
    assert_eq!((steps.len(), bends.len()), (2, 2));
    assert!(steps.iter().all(|s| s.as_f64().unwrap() > 0.0));
    // The finest of several levels is left unbent.
    assert_eq!(bends[1].as_f64(), Some(0.0));
    let text = common::ok(&common::swm(&["info", &bare]));
    assert!(text.contains("base                  bare"), "{text}");
    assert!(text.contains("prediction            loop"), "{text}");
    assert!(!text.contains("CLERS"), "{text}");
    // The first 1.2 file: a whole mode-0 file in BASE, no bends.
    let first = golden("displaced-v1.2.swm");
    let v = common::json(&common::swm(&["info", &first, "--json"]));
    assert_eq!(v["bare_base"], false);
    assert_eq!(v["base_bytes"], 923);
    assert!(v["bends"]
        .as_array()
        .unwrap()
        .iter()
        .all(|b| b.as_f64() == Some(0.0)));
}
