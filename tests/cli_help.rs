//! The help texts and the README in step (issue 23, item 8): every long
//! option `swm SUB --help` lists is named on one of the README's usage
//! lines for SUB (in the Usage section's code blocks), and every option
//! a usage line names is one SUB accepts. A new option without a README
//! line, or a README line for an option that is gone, fails here.

mod common;
use common::*;
use std::collections::BTreeSet;

const SUBCOMMANDS: [&str; 7] = [
    "encode", "decode", "info", "distance", "sharpen", "rd", "render",
];

/// An option as `--help` lists it: its long name and its short one.
#[derive(Debug)]
struct Listed {
    long: String,
    short: Option<String>,
}

/// The options of `swm SUB --help`: the lines that start (after the
/// indentation) with `-x, --name` or `--name`; options named in the
/// prose of a description are not options of SUB.
fn help_options(sub: &str) -> Vec<Listed> {
    let help = ok(&swm(&[sub, "--help"]));
    let mut listed = Vec::new();
    for line in help.lines() {
        let line = line.trim_start();
        let mut words = line.split_whitespace();
        let (short, long) = match words.next() {
            Some(w) if w.starts_with("--") => (None, w),
            Some(w) if w.len() == 3 && w.starts_with('-') && w.ends_with(',') => {
                (Some(w.trim_end_matches(',')), words.next().unwrap_or(""))
            }
            _ => continue,
        };
        if !long.starts_with("--") {
            continue;
        }
        listed.push(Listed {
            long: long.to_string(),
            short: short.map(str::to_string),
        });
    }
    listed
        .into_iter()
        .filter(|o| o.long != "--help" && o.long != "--version")
        .collect()
}

/// The README's Usage section: from `## Usage` to the next `## ` heading
/// (its `###` subsections included).
fn usage_section() -> String {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md"))
        .expect("README.md");
    let start = readme.find("\n## Usage\n").expect("a Usage section");
    let rest = &readme[start + 1..];
    let end = rest[3..].find("\n## ").map_or(rest.len(), |e| e + 3);
    rest[..end].to_string()
}

/// The usage lines for `sub`: lines of the section's code blocks that
/// run `swm SUB`, their `#` comments cut off.
fn usage_lines(section: &str, sub: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut in_code = false;
    for line in section.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        let command = line.split(" #").next().unwrap_or("").trim();
        let mut words = command.split_whitespace();
        if in_code && words.next() == Some("swm") && words.next() == Some(sub) {
            lines.push(command.to_string());
        }
    }
    lines
}

/// The options a usage line names: `--name` and `-x` words, split at the
/// brackets and bars of the synopsis.
fn named_options(line: &str) -> BTreeSet<String> {
    line.split(|c: char| c.is_whitespace() || "[]|()=,".contains(c))
        .filter(|w| {
            let long = w.starts_with("--") && w.len() > 2;
            let short = w.len() == 2 && w.starts_with('-') && w.as_bytes()[1].is_ascii_alphabetic();
            long || short
        })
        .map(str::to_string)
        .collect()
}

#[test]
fn every_option_of_every_subcommand_is_in_the_readme_usage() {
    let section = usage_section();
    let mut missing = Vec::new();
    for sub in SUBCOMMANDS {
        let lines = usage_lines(&section, sub);
        assert!(
            !lines.is_empty(),
            "the README has no usage line for `swm {sub}`"
        );
        let named: BTreeSet<String> = lines.iter().flat_map(|l| named_options(l)).collect();
        let listed = help_options(sub);
        assert!(
            !listed.is_empty() || sub == "info",
            "{sub}: no options parsed from --help"
        );
        for o in &listed {
            let short_named = o.short.as_ref().is_some_and(|s| named.contains(s));
            if !named.contains(&o.long) && !short_named {
                missing.push(format!("swm {sub} {}", o.long));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "options --help lists that no README usage line names: {missing:?}"
    );
}

#[test]
fn every_option_the_readme_names_is_accepted() {
    let section = usage_section();
    let mut unknown = Vec::new();
    for sub in SUBCOMMANDS {
        let listed = help_options(sub);
        let accepted: BTreeSet<&str> = listed
            .iter()
            .flat_map(|o| std::iter::once(o.long.as_str()).chain(o.short.as_deref()))
            .collect();
        for line in usage_lines(&section, sub) {
            for option in named_options(&line) {
                if !accepted.contains(option.as_str()) {
                    unknown.push(format!("{line}: {option}"));
                }
            }
        }
    }
    assert!(
        unknown.is_empty(),
        "README usage lines name options --help does not list: {unknown:?}"
    );
}

/// The parsers above on what they must tell apart: a description that
/// mentions another option is not an option line.
#[test]
fn help_parsing_skips_options_named_in_prose() {
    let encode = help_options("encode");
    let longs: Vec<&str> = encode.iter().map(|o| o.long.as_str()).collect();
    assert!(
        longs.contains(&"--output") && longs.contains(&"--max-work"),
        "{longs:?}"
    );
    // `encode --help` says "files to be decoded with --sharpen".
    assert!(!longs.contains(&"--sharpen"), "{longs:?}");
    let output = encode.iter().find(|o| o.long == "--output").unwrap();
    assert_eq!(output.short.as_deref(), Some("-o"));
    assert_eq!(
        named_options("swm rd --check TABLE.csv [--only MESH]... [--tolerance 0.01] -o x"),
        ["--check", "--only", "--tolerance", "-o"]
            .map(String::from)
            .into_iter()
            .collect()
    );
}
