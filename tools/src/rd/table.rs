//! The rd table: one row per (mesh, rate, configuration), written as CSV
//! (the regression record that `--check` reads back), Markdown (for
//! people) and JSON (`--json`).
//!
//! CSV columns, in order (readers find them by name, so more may be added):
//!
//! | column | meaning |
//! |---|---|
//! | `mesh` | the mesh, as `rd::source` names it |
//! | `rate_bpv` | the target rate, bits per input vertex |
//! | `config` | the configuration (`lossless`, `baseline`, `auto`, `swing`, ...) |
//! | `effort` | the effort level of the automatic mode (`swm encode --effort`): `max` for `auto`, `default` for `auto-default`, `fast` for `auto-fast`; empty for the configurations that pin one method and its search (`lossless`, `baseline`, the swing rows). A function of `config`, written so that readers can group by it; a table that contradicts its config is refused, and one written before the column existed reads as if it had it |
//! | `status` | `ok`; `infeasible` when nothing fits the budget; `failed` when the encoder gave up (the reason is printed on stderr); `n/a` when the configuration does not take the mesh (e.g. `swing` on a mesh with holes) |
//! | `vertices` | vertex count of the mesh as read (the rate's unit) |
//! | `budget_bytes` | ⌊rate × vertices / 8⌋ |
//! | `bytes` | size of the `.swm` file |
//! | `bpv` | actual bits per input vertex, 8 × bytes / vertices |
//! | `faces` | triangles of the decoded mesh |
//! | `qp` | quantization bits: per coordinate (`lossless`, `baseline`), per dihedral angle (`swing`) |
//! | `samples` | area-proportional face samples per direction of the final distance |
//! | `l2_rel` | L2 (max of the one-sided RMS), in 1e-4 of the input's bbox diagonal |
//! | `hausdorff_rel` | Hausdorff distance, same unit |
//! | `encode_s`, `decode_s` | wall times (simplification included in the baseline's encode, the rate search in swing's, the whole chooser in auto's) |
//! | `method` | how the file codes the mesh: `swing` (retiled), `simplified` (simplified, then lossless), `whole` (the whole mesh, lossless, at the quantization the simplified method chose: nothing more to code), `lossless` (the `lossless` row), `displaced` (displaced subdivision: a simplified base and levels of scalars; `qp` is its base's), `mixed` (a method per component); for `auto`, the method it chose |
//!
//! Rows without a file (every status but `ok`) leave the measured columns
//! empty. Numbers other than
//! times are printed in Rust's shortest round-trip form, so a table read
//! back compares bit for bit with a fresh run.
//!
//! The CSV is plain (RFC 4180): the header is its first line, so that
//! Python's `csv.DictReader` and pandas' `read_csv` find the columns
//! without options. The units, which tables used to carry in a leading
//! `#` comment (taken as the header by those readers), are in the
//! README's `swm rd` section and in the Markdown written beside the CSV.
//! Lines starting with `#` are still skipped when a table is read, so
//! `--check` reads tables written before.

use crate::rd::config::Config;
use serde_json::{json, Value};
use swm::{FormatError, Location, Malformed};

/// How a configuration fared at one rate.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// A file within the budget, decoded and measured.
    Coded(Coded),
    /// Nothing the configuration makes fits the budget.
    Infeasible,
    /// The encoder gave up (e.g. the retiler found no working edge
    /// length); `why` is its message, empty when read back from a table.
    Failed {
        /// The library's error message.
        why: String,
    },
    /// The configuration does not take this mesh (e.g. `swing` on a mesh
    /// that is not one closed genus-0 surface); `why` as for `Failed`.
    NotApplicable {
        /// The library's error message.
        why: String,
    },
}

impl Outcome {
    /// The status column: `ok`, `infeasible`, `failed` or `n/a`.
    pub fn status(&self) -> &'static str {
        match self {
            Outcome::Coded(_) => "ok",
            Outcome::Infeasible => "infeasible",
            Outcome::Failed { .. } => "failed",
            Outcome::NotApplicable { .. } => "n/a",
        }
    }

    /// The file's figures, when there is a file.
    pub fn coded(&self) -> Option<&Coded> {
        match self {
            Outcome::Coded(c) => Some(c),
            _ => None,
        }
    }

    /// What a table cell shows instead of a number when there is no file.
    pub fn placeholder(&self) -> &'static str {
        match self {
            Outcome::Failed { .. } => "failed",
            Outcome::NotApplicable { .. } => "n/a",
            _ => "—",
        }
    }
}

/// What a configuration produced at one rate.
#[derive(Clone, Debug, PartialEq)]
pub struct Coded {
    /// Size of the `.swm` file.
    pub bytes: u64,
    /// Triangles of the decoded mesh.
    pub faces: u64,
    /// Quantization bits: per coordinate (lossless, baseline) or per
    /// dihedral angle (swing).
    pub qp: u8,
    /// L2 distance, 1e-4 of the diagonal.
    pub l2_rel: f64,
    /// Hausdorff distance, 1e-4 of the diagonal.
    pub hausdorff_rel: f64,
    /// Seconds to encode (and simplify, for the baseline).
    pub encode_s: f64,
    /// Seconds to decode.
    pub decode_s: f64,
    /// How the file codes the mesh: `swing`, `simplified`, `whole` or
    /// `lossless` (empty when read from a table written before).
    pub method: String,
}

/// One row of the table.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The mesh, as the table names it.
    pub mesh: String,
    /// Target bits per input vertex.
    pub rate_bpv: f64,
    /// The configuration.
    pub config: Config,
    /// Vertices of the mesh as read.
    pub vertices: u64,
    /// Byte budget derived from the rate.
    pub budget_bytes: u64,
    /// Face samples per direction of the final distance measurement.
    pub samples: u64,
    /// The outcome.
    pub outcome: Outcome,
}

impl Row {
    /// `ok`, `infeasible`, `failed` or `n/a`.
    pub fn status(&self) -> &'static str {
        self.outcome.status()
    }

    /// The file's figures, when there is a file.
    pub fn coded(&self) -> Option<&Coded> {
        self.outcome.coded()
    }

    /// Actual bits per input vertex.
    pub fn bpv(&self) -> Option<f64> {
        let c = self.coded()?;
        Some(8.0 * c.bytes as f64 / self.vertices.max(1) as f64)
    }

    /// How verdicts and messages name the row.
    pub fn key(&self) -> String {
        format!("{} {} bpv {}", self.mesh, self.rate_bpv, self.config.name())
    }

    /// The row as a JSON object with the CSV's keys (`null` when empty).
    pub fn to_json(&self) -> Value {
        let c = self.coded();
        json!({
            "mesh": self.mesh,
            "rate_bpv": self.rate_bpv,
            "config": self.config.name(),
            "effort": self.config.effort().map(|e| e.name()),
            "status": self.status(),
            "vertices": self.vertices,
            "budget_bytes": self.budget_bytes,
            "bytes": c.map(|c| c.bytes),
            "bpv": self.bpv(),
            "faces": c.map(|c| c.faces),
            "qp": c.map(|c| c.qp),
            "samples": self.samples,
            "l2_rel": c.map(|c| c.l2_rel),
            "hausdorff_rel": c.map(|c| c.hausdorff_rel),
            "encode_s": c.map(|c| c.encode_s),
            "decode_s": c.map(|c| c.decode_s),
            "method": c.map(|c| c.method.clone()),
        })
    }
}

/// The CSV columns, in the order written.
pub const COLUMNS: [&str; 17] = [
    "mesh",
    "rate_bpv",
    "config",
    "effort",
    "status",
    "vertices",
    "budget_bytes",
    "bytes",
    "bpv",
    "faces",
    "qp",
    "samples",
    "l2_rel",
    "hausdorff_rel",
    "encode_s",
    "decode_s",
    "method",
];

/// The table as CSV.
pub fn to_csv(rows: &[Row]) -> String {
    // No comment line before the header: see the module header.
    let mut out = COLUMNS.join(",");
    out.push('\n');
    for r in rows {
        let c = r.coded();
        let opt = |v: Option<String>| v.unwrap_or_default();
        let cells = [
            csv_cell(&r.mesh),
            r.rate_bpv.to_string(),
            r.config.name().to_string(),
            effort_cell(r.config).to_string(),
            r.status().to_string(),
            r.vertices.to_string(),
            r.budget_bytes.to_string(),
            opt(c.map(|c| c.bytes.to_string())),
            opt(r.bpv().map(|b| b.to_string())),
            opt(c.map(|c| c.faces.to_string())),
            opt(c.map(|c| c.qp.to_string())),
            r.samples.to_string(),
            opt(c.map(|c| c.l2_rel.to_string())),
            opt(c.map(|c| c.hausdorff_rel.to_string())),
            opt(c.map(|c| format!("{:.4}", c.encode_s))),
            opt(c.map(|c| format!("{:.4}", c.decode_s))),
            opt(c.map(|c| c.method.clone())),
        ];
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// The `effort` cell of a configuration's rows: empty for those that do
/// not run the automatic mode.
fn effort_cell(config: Config) -> &'static str {
    config.effort().map_or("", |e| e.name())
}

/// Mesh names are the only free text; quote them when they need it.
fn csv_cell(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Splits one CSV line, honouring double quotes.
fn split_csv(line: &str) -> Option<Vec<String>> {
    let mut cells = Vec::new();
    let mut cell = String::new();
    let mut chars = line.chars().peekable();
    let mut quoted = false;
    while let Some(ch) = chars.next() {
        match (quoted, ch) {
            (true, '"') if chars.peek() == Some(&'"') => {
                cell.push('"');
                chars.next();
            }
            (true, '"') => quoted = false,
            (false, '"') if cell.is_empty() => quoted = true,
            (false, ',') => cells.push(std::mem::take(&mut cell)),
            (_, c) => cell.push(c),
        }
    }
    if quoted {
        return None;
    }
    cells.push(cell);
    Some(cells)
}

/// A CSV error at a line.
fn bad(line: usize, why: &'static str) -> swm::Error {
    FormatError::new("CSV", Malformed::BadSyntax(why))
        .at(Location::Line(line as u64))
        .into()
}

/// Reads a table written by [`to_csv`]. Columns are found by name;
/// lines starting with `#` (the units note of tables written before the
/// CSV became plain) are skipped.
pub fn from_csv(text: &str) -> Result<Vec<Row>, swm::Error> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim_end_matches('\r')))
        .filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('#'));
    let Some((header_line, header)) = lines.next() else {
        return Err(FormatError::new("CSV", Malformed::Empty).into());
    };
    let header =
        split_csv(header).ok_or_else(|| bad(header_line, "unbalanced quotes in the header"))?;
    let col = |name: &str| header.iter().position(|h| h.trim() == name);
    let mut index = [0usize; COLUMNS.len()];
    for (slot, name) in index.iter_mut().zip(COLUMNS) {
        // Times are informative only, and `method` and `effort` came
        // later; every other column is needed.
        *slot = match col(name) {
            Some(i) => i,
            None if name.ends_with("_s") || name == "method" || name == "effort" => usize::MAX,
            None => return Err(bad(header_line, "the header lacks a column swm rd writes")),
        };
    }
    let mut rows = Vec::new();
    for (n, line) in lines {
        let cells = split_csv(line).ok_or_else(|| bad(n, "unbalanced quotes"))?;
        if cells.len() != header.len() {
            return Err(bad(
                n,
                "the row has a different number of cells than the header",
            ));
        }
        let get = |name: &str| {
            let k = COLUMNS.iter().position(|c| *c == name).expect("a column");
            cells.get(index[k]).map(|s| s.trim())
        };
        rows.push(parse_row(n, get)?);
    }
    Ok(rows)
}

/// One row from its cells by column name (`None`: a column the table
/// lacks, which `from_csv` allows only for the optional ones).
fn parse_row<'a>(n: usize, cell: impl Fn(&str) -> Option<&'a str>) -> Result<Row, swm::Error> {
    fn num<T: std::str::FromStr>(n: usize, s: &str, why: &'static str) -> Result<T, swm::Error> {
        s.parse().map_err(|_| bad(n, why))
    }
    let get = |name: &str| cell(name).unwrap_or("");
    let rate_bpv: f64 = num(n, get("rate_bpv"), "rate_bpv is not a number")?;
    if !(rate_bpv.is_finite() && rate_bpv > 0.0) {
        return Err(bad(n, "rate_bpv must be positive"));
    }
    let config = Config::from_name(get("config")).ok_or_else(|| bad(n, "unknown config"))?;
    // The level is the configuration's; a table that says otherwise
    // describes runs this harness does not make.
    if cell("effort").is_some_and(|e| e != effort_cell(config)) {
        return Err(bad(n, "effort does not match the config"));
    }
    let outcome = match get("status") {
        "infeasible" => Outcome::Infeasible,
        "failed" => Outcome::Failed { why: String::new() },
        "n/a" => Outcome::NotApplicable { why: String::new() },
        "ok" => Outcome::Coded(Coded {
            bytes: num(n, get("bytes"), "bytes is not a whole number")?,
            faces: num(n, get("faces"), "faces is not a whole number")?,
            qp: num(n, get("qp"), "qp is not a whole number")?,
            l2_rel: num(n, get("l2_rel"), "l2_rel is not a number")?,
            hausdorff_rel: num(n, get("hausdorff_rel"), "hausdorff_rel is not a number")?,
            encode_s: get("encode_s").parse().unwrap_or(f64::NAN),
            decode_s: get("decode_s").parse().unwrap_or(f64::NAN),
            method: get("method").to_string(),
        }),
        _ => return Err(bad(n, "status must be ok, infeasible, failed or n/a")),
    };
    let samples: u64 = num(n, get("samples"), "samples is not a whole number")?;
    if samples == 0 {
        return Err(bad(n, "samples must be at least 1"));
    }
    Ok(Row {
        mesh: get("mesh").to_string(),
        rate_bpv,
        config,
        vertices: num(n, get("vertices"), "vertices is not a whole number")?,
        budget_bytes: num(n, get("budget_bytes"), "budget_bytes is not a whole number")?,
        samples,
        outcome,
    })
}

/// How a pivot table shows one measure of a row.
type Show = fn(&Coded) -> String;

/// The table as Markdown: per mesh, L2 and Hausdorff by rate and
/// configuration (the layout of the thesis tables), then every row.
pub fn to_markdown(title: &str, rows: &[Row], short_name: impl Fn(&str) -> String) -> String {
    let mut out = format!("# swm rd: {title}\n\n");
    out.push_str(
        "L2 and Hausdorff distances in units of 1e-4 of the input's bounding-box diagonal; \
         rates in bits per vertex of the mesh as read. `—` = nothing fits the budget, \
         `failed` = the encoder gave up, `n/a` = the configuration does not take the mesh. \
         `auto`, `auto-default` and `auto-fast` are `swm encode` at `--effort max`, with no flag \
         (`default`) and at `--effort fast` (the `effort` column); `baseline` is the simplified method \
         alone (`--mode lossless` at the size) and `displaced` displaced subdivision alone \
         (`--mode displaced`). \
         Written by `swm rd`; the CSV beside this file is the record `swm rd --check` compares against \
         (its `l2_rel` and `hausdorff_rel` in the same units, `rate_bpv` and `bpv` in bits per vertex, \
         `encode_s` and `decode_s` in seconds).\n",
    );
    let mut meshes: Vec<&str> = Vec::new();
    let mut rates: Vec<f64> = Vec::new();
    for r in rows {
        if !meshes.contains(&r.mesh.as_str()) {
            meshes.push(&r.mesh);
        }
        if !rates.contains(&r.rate_bpv) {
            rates.push(r.rate_bpv);
        }
    }
    rates.sort_by(f64::total_cmp);
    for mesh in &meshes {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.mesh == *mesh).collect();
        let vertices = mine.first().map_or(0, |r| r.vertices);
        out.push_str(&format!(
            "\n## {} (`{mesh}`, {vertices} vertices)\n\n",
            short_name(mesh)
        ));
        out.push_str("| config | metric |");
        for r in &rates {
            out.push_str(&format!(" {r} |"));
        }
        out.push_str("\n|---|---|");
        out.push_str(&"---:|".repeat(rates.len()));
        out.push('\n');
        let mut configs: Vec<Config> = mine.iter().map(|r| r.config).collect();
        configs.sort();
        configs.dedup();
        let metrics: [(&str, Show); 4] = [
            ("L2", |c| format!("{:.3}", c.l2_rel)),
            ("Hausdorff", |c| format!("{:.2}", c.hausdorff_rel)),
            ("bytes", |c| c.bytes.to_string()),
            ("method", |c| c.method.clone()),
        ];
        for config in configs {
            // Which method wrote the file is news only where a choice is
            // made: the automatic mode's rows, at every effort.
            let shown = if config.effort().is_some() { 4 } else { 3 };
            for (metric, show) in metrics.into_iter().take(shown) {
                out.push_str(&format!("| {} | {metric} |", config.name()));
                for rate in &rates {
                    let cell = mine
                        .iter()
                        .find(|r| r.config == config && r.rate_bpv == *rate)
                        .map(|r| r.coded().map_or(r.outcome.placeholder().to_string(), show))
                        .unwrap_or_default();
                    out.push_str(&format!(" {cell} |"));
                }
                out.push('\n');
            }
        }
    }
    out.push_str("\n## All rows\n\n");
    out.push_str("| mesh | rate | config | effort | status | budget | bytes | bpv | faces | qp | L2 | Hausdorff | encode s | decode s |\n");
    out.push_str("|---|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for r in rows {
        let head = format!(
            "| {} | {} | {} | {} | {} | {} |",
            short_name(&r.mesh),
            r.rate_bpv,
            r.config.name(),
            effort_cell(r.config),
            r.status(),
            r.budget_bytes
        );
        out.push_str(&head);
        match (r.coded(), r.bpv()) {
            (Some(c), Some(bpv)) => out.push_str(&format!(
                " {} | {bpv:.3} | {} | {} | {:.3} | {:.2} | {:.3} | {:.4} |\n",
                c.bytes, c.faces, c.qp, c.l2_rel, c.hausdorff_rel, c.encode_s, c.decode_s
            )),
            _ => out.push_str(&(" |".repeat(8) + "\n")),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{from_csv, to_csv, to_markdown, Coded, Outcome, Row};
    use crate::rd::config::Config;

    fn row(config: Config, rate_bpv: f64, outcome: Outcome) -> Row {
        Row {
            mesh: "generated:torus".into(),
            rate_bpv,
            config,
            vertices: 1536,
            budget_bytes: (rate_bpv * 1536.0 / 8.0) as u64,
            samples: 1000,
            outcome,
        }
    }

    /// Every status survives the CSV (reasons are not stored) and shows
    /// in the Markdown.
    #[test]
    fn every_status_round_trips() {
        let coded = Coded {
            bytes: 380,
            faces: 590,
            qp: 8,
            l2_rel: 0.1 + 0.2,
            hausdorff_rel: 1.0 / 3.0,
            encode_s: 0.25,
            decode_s: 0.0625,
            method: "swing".into(),
        };
        let why = "because".to_string();
        let rows = vec![
            row(Config::Swing, 2.0, Outcome::Coded(coded)),
            row(Config::Lossless, 1.0, Outcome::Infeasible),
            row(Config::Swing, 1.0, Outcome::Failed { why: why.clone() }),
            row(Config::Swing, 4.0, Outcome::NotApplicable { why }),
        ];
        let csv = to_csv(&rows);
        assert!(csv.starts_with("mesh,rate_bpv,config,"), "plain CSV: {csv}");
        let back = from_csv(&csv).expect("a table");
        // Tables written with the old comment line read the same.
        let old = format!("# swm rd table: units\n{csv}");
        assert_eq!(from_csv(&old).expect("an old table"), back);
        let statuses: Vec<&str> = back.iter().map(Row::status).collect();
        assert_eq!(statuses, ["ok", "infeasible", "failed", "n/a"]);
        assert_eq!(back[0], rows[0], "numbers round-trip bit for bit");
        assert_eq!(back[2].outcome, Outcome::Failed { why: String::new() });
        // A table written before the effort column reads the same.
        let without: String = csv
            .lines()
            .map(|l| {
                let mut cells: Vec<&str> = l.split(',').collect();
                cells.remove(3);
                cells.join(",") + "\n"
            })
            .collect();
        assert!(
            without.starts_with("mesh,rate_bpv,config,status,"),
            "{without}"
        );
        assert_eq!(from_csv(&without).expect("a table without effort"), back);
        let md = to_markdown("t", &rows, |m| m.to_string());
        assert!(md.contains("| swing | L2 | failed | 0.300 | n/a |"), "{md}");
        assert!(md.contains("| lossless | L2 | — |"), "{md}");
    }

    /// The `effort` column names the automatic mode's level, and a table
    /// whose level contradicts its configuration is refused.
    #[test]
    fn effort_column_follows_the_config() {
        let rows = vec![
            row(Config::Baseline, 1.0, Outcome::Infeasible),
            row(Config::Auto, 1.0, Outcome::Infeasible),
            row(Config::AutoDefault, 1.0, Outcome::Infeasible),
            row(Config::AutoFast, 1.0, Outcome::Infeasible),
        ];
        let csv = to_csv(&rows);
        let efforts: Vec<&str> = csv
            .lines()
            .map(|l| l.split(',').nth(3).expect("an effort cell"))
            .collect();
        assert_eq!(efforts, ["effort", "", "max", "default", "fast"]);
        assert_eq!(from_csv(&csv).expect("a table"), rows);
        let json = rows[2].to_json();
        assert_eq!(json["effort"], "default");
        assert!(rows[0].to_json()["effort"].is_null());
        let wrong = csv.replacen(",auto,max,", ",auto,fast,", 1);
        let err = from_csv(&wrong).expect_err("auto is max").to_string();
        assert!(err.contains("line 3") && err.contains("effort"), "{err}");
        let md = to_markdown("t", &rows, |m| m.to_string());
        assert!(md.contains("| auto-fast | method |"), "{md}");
        assert!(
            md.contains("| 1 | auto-default | default | infeasible |"),
            "{md}"
        );
    }
}
