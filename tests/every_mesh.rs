//! Issue 20, "every mesh, every rate": the default mode over the whole
//! matrix of meshes (the shared corpus and the generated one) and rates
//! (0.5, 1, 2, 4 and 8 bits per vertex).
//!
//! Two halves. The committed regression tables (`corpus/rd/*.csv`, made
//! by `swm rd` with the library's `auto` mode, which `swm encode` runs;
//! `tests/rd.rs` checks that the generated table and the fandisk rows
//! are what the code makes today) must show, for every cell: a file
//! within 3% of the request, or the whole mesh (nothing more to code),
//! or a file short of it only where every file on size has more than 5%
//! more error; a refusal only as "nothing that small"; and an error no
//! more than 5% above the better of `swing` and `baseline`. And the
//! generated meshes are encoded here through the command line at every
//! rate: the decoded mesh is manifold and keeps every component.

mod common;
use common::*;

use std::collections::BTreeMap;

const RATES: [&str; 5] = ["0.5", "1", "2", "4", "8"];

/// One table's rows by (mesh, rate, config), each a map of its columns.
type Table = BTreeMap<(String, String, String), BTreeMap<String, String>>;

fn table(name: &str) -> Table {
    let path = format!("{}/../corpus/rd/{name}.csv", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines
        .map(|l| {
            let row: BTreeMap<String, String> = header
                .iter()
                .zip(l.split(','))
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect();
            let key = (
                row["mesh"].clone(),
                row["rate_bpv"].clone(),
                row["config"].clone(),
            );
            (key, row)
        })
        .collect()
}

fn num(row: &BTreeMap<String, String>, col: &str) -> f64 {
    row[col].parse().unwrap_or(f64::NAN)
}

/// The matrix's verdicts for one table; returns the cells checked.
fn check_table(name: &str, meshes: usize) -> usize {
    let t = table(name);
    let cells: Vec<(String, String)> = t
        .keys()
        .filter(|k| k.2 == "auto")
        .map(|k| (k.0.clone(), k.1.clone()))
        .collect();
    assert_eq!(
        cells.len(),
        meshes * RATES.len(),
        "{name}: not the whole matrix"
    );
    let mut problems = Vec::new();
    for (mesh, rate) in &cells {
        let get = |config: &str| t.get(&(mesh.clone(), rate.clone(), config.to_string()));
        let auto = get("auto").unwrap();
        let cell = format!("{mesh} {rate} b/v");
        match auto["status"].as_str() {
            "ok" => {}
            // Below the smallest file: `swm encode` names the smallest.
            "infeasible" => continue,
            other => {
                problems.push(format!("{cell}: {other}"));
                continue;
            }
        }
        let budget = num(auto, "budget_bytes");
        let bytes = num(auto, "bytes");
        let l2 = num(auto, "l2_rel");
        let on_size = |r: &BTreeMap<String, String>| {
            r["status"] == "ok" && num(r, "bytes") >= 0.97 * num(r, "budget_bytes")
        };
        let method = auto["method"].as_str();
        assert!(
            ["swing", "simplified", "displaced", "whole"].contains(&method),
            "{cell}: method {method:?}"
        );
        if bytes > budget {
            problems.push(format!("{cell}: {bytes} bytes over {budget}"));
        }
        if !on_size(auto) && method != "whole" {
            // Short: only where every file on size is more than 5% worse.
            let better_on_size = ["swing", "baseline"]
                .iter()
                .filter_map(|c| get(c))
                .any(|r| on_size(r) && num(r, "l2_rel") <= 1.05 * l2);
            if better_on_size {
                problems.push(format!("{cell}: {bytes} bytes for {budget}"));
            }
        }
        let better = ["swing", "baseline"]
            .iter()
            .filter_map(|c| get(c))
            .filter(|r| r["status"] == "ok")
            .map(|r| num(r, "l2_rel"))
            .fold(f64::INFINITY, f64::min);
        if l2 > 1.05 * better {
            problems.push(format!("{cell}: L2 {l2} against {better}"));
        }
    }
    assert!(problems.is_empty(), "{name}: {problems:#?}");
    cells.len()
}

#[test]
fn the_committed_tables_answer_every_cell() {
    assert_eq!(check_table("shared", 12), 60);
    assert_eq!(check_table("generated", 7), 35);
}

/// Issue 20's CAD bar: on fandisk the default mode is at or below the
/// L2 of quadric simplification + Draco (`../shared/corpus/README.md`,
/// 1e-4 of the diagonal) at every rate. `tests/rd.rs` re-runs these rows
/// against the code, so the committed figures are today's.
#[test]
fn fandisk_default_is_at_or_below_quadric_and_draco() {
    const DRACO: [f64; 5] = [12.32, 8.09, 1.36, 0.43, 0.12];
    let t = table("shared");
    for (rate, draco) in RATES.iter().zip(DRACO) {
        let key = (
            "shared:fandisk.obj".to_string(),
            rate.to_string(),
            "auto".to_string(),
        );
        let row = &t[&key];
        assert_eq!(row["status"], "ok", "fandisk {rate} b/v");
        let l2 = num(row, "l2_rel");
        assert!(
            l2 <= draco,
            "fandisk {rate} b/v: L2 {l2} above Draco's {draco}"
        );
    }
}

/// What the default mode writes for every generated mesh at every rate,
/// through the command line as a user runs it: refused with the smallest
/// size, or a file that decodes to a manifold mesh with as many
/// components as the cleaned input.
#[test]
fn generated_meshes_encode_at_every_rate() {
    let dir = scratch("every-mesh");
    let out = dir.join("m.swm");
    for (name, mesh) in swm_corpus::all() {
        let input = dir.join(format!("{name}.obj"));
        swm::io::write_mesh(&input, &mesh).unwrap();
        let cleaned = swm::clean(&mesh, &Default::default()).unwrap();
        let components = cleaned.table.components().len();
        for rate in RATES {
            let o = swm(&[
                "encode",
                input.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
                "--bpv",
                rate,
                "--json",
            ]);
            let cell = format!("{name} {rate} b/v");
            if o.status.code() == Some(1) {
                let err = String::from_utf8_lossy(&o.stderr);
                assert!(err.contains("the smallest possible is"), "{cell}: {err}");
                continue;
            }
            let j = json(&o);
            let within = j["size"]["within_tolerance"].as_bool().unwrap();
            let whole = j["size"]["whole_mesh_short"].as_bool().unwrap();
            let decoded = swm::decode(&std::fs::read(&out).unwrap(), &Default::default()).unwrap();
            let table = swm::CornerTable::new(&decoded.triangles, decoded.vertex_count())
                .unwrap_or_else(|e| panic!("{cell}: decoded not manifold: {e}"));
            assert_eq!(table.components().len(), components, "{cell}: a piece lost");
            println!("{cell}: {} bytes, {}", j["bytes"], j["method"]["chosen"]);
            // Never more than 3% above the request; off size only for a
            // lower error: the automatic mode keeps a file within 3% of
            // the request over one further short of it unless the short
            // one is closer to the input by a margin (encoder/choose.rs),
            // or the whole mesh is short of the request.
            let requested = j["size"]["requested"].as_f64().unwrap();
            let bytes = j["bytes"].as_f64().unwrap();
            assert!(
                bytes <= 1.03 * requested,
                "{cell}: {bytes} bytes for {requested}"
            );
            // `within_tolerance`'s own rule (tools/src/encode.rs).
            let on_size = |b: f64| b * 100.0 >= requested * 97.0 && b * 100.0 <= requested * 103.0;
            assert_eq!(
                within,
                on_size(bytes),
                "{cell}: {bytes} bytes of {requested}"
            );
            if !within && !whole {
                let chosen = j["method"]["chosen"].as_str().unwrap();
                let l2 = j["method"][chosen]["l2_rel"].as_f64();
                for c in j["method"]["candidates"].as_array().unwrap() {
                    let f = &c["file"];
                    if f.is_object() && on_size(f["bytes"].as_f64().unwrap()) {
                        let other = f["l2_rel"].as_f64().unwrap();
                        assert!(
                            l2.is_some_and(|l2| l2 < other),
                            "{cell}: off size at {bytes} of {requested} though {} was on size \
                             and no farther: {}",
                            c["method"],
                            j["method"]
                        );
                    }
                }
            }
        }
    }
}
