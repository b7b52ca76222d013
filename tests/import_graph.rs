//! The file-level import graph of `codec/src` and `tools/src` has no
//! cycle (issue 45, "No import cycles"): a reader can start at the bottom
//! of each crate and read upwards, and a module can be moved or replaced
//! without dragging the modules above it along.
//!
//! The rule this test reads the sources by:
//! - A node is a `.rs` file; an inline `mod x { … }` belongs to its file.
//! - Edge A → B when A names an item through a path that resolves to B:
//!   `use crate::…`, `use super::…`, `use self::…`, `use child::…`, and
//!   paths in code (`crate::swing::retile::rate::Knobs`, `super::fill::Piece`,
//!   `child::f()`, or `alias::f()` after `use crate::swing::retile as alias`).
//!   A module path resolves to the longest prefix that is a module
//!   (`x.rs`, `x/mod.rs` or an inline module, which maps to its file).
//! - Re-exports are followed: `crate::TriMesh` resolves to the file that
//!   defines `TriMesh`, not to `lib.rs`, whose `pub use` is itself an
//!   edge `lib.rs` → that file. So a parent's `pub use child::Thing` is
//!   an edge parent → child, and the crate root as a facade is no cycle.
//! - A glob `use m::*` is an edge to m's file when m defines items of its
//!   own, and to where each of m's `pub` re-exports resolves (so
//!   `crate::prelude::*`, which only re-exports `alloc`, is no edge).
//! - `mod foo;` alone is no edge: a parent declaring a child imports
//!   nothing from it.
//! - Test code counts, as a node of its own: a `#[cfg(test)]` module,
//!   inline (`codec/src/io/obj.rs#tests`) or a file (`retile/tests.rs`),
//!   is a separate node whose imports are edges like any other. A module's
//!   own tests may call the API above it (`obj.rs`'s tests read through
//!   `io::read_mesh_bytes`) without that making the module import its
//!   caller; and since no production code can import test code, a cycle
//!   through tests is one among test modules (helpers that import each
//!   other). Shared test helpers belong in test-support modules low
//!   enough for every test that takes them (`mesh/test_shapes.rs`).
//! - Comments, doc comments, string and character literals are blanked
//!   before scanning; lifetimes are dropped. Macro names (`say!`) and
//!   `pub(in path)` visibilities are not imports.
//!
//! The test prints every cycle (a strongly connected component of more
//! than one file) with the references that close it, and fails unless the
//! component lies within an entry of `ALLOWED_FOR_NOW`.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::{Path, PathBuf};

/// Cycles tolerated for now. Each entry is a set of files; a cycle passes
/// when all its files lie in one entry. Empty since issue 45 broke the
/// last ones, and to stay so: the test fails when an entry no longer
/// meets any cycle, and no entry may be added.
const ALLOWED_FOR_NOW: &[&[&str]] = &[];

type Module = Vec<String>;

/// One crate's sources: every module (file or inline) and what each file
/// refers to.
#[derive(Default)]
struct Crate {
    /// Module path → the file (index into `files`) that holds it.
    modules: BTreeMap<Module, usize>,
    /// Modules that define an item of their own (fn, struct, …).
    defines_items: BTreeSet<Module>,
    /// Per module: name → (binding's module, raw path, is it `pub`).
    bindings: HashMap<Module, Vec<Binding>>,
    /// Per module: glob imports (raw paths), for name lookup.
    globs: HashMap<Module, Vec<(Vec<String>, bool)>>,
    files: Vec<String>,
    refs: Vec<Reference>,
}

struct Binding {
    name: String,
    path: Vec<String>,
    public: bool,
}

struct Reference {
    file: usize,
    module: Module,
    line: usize,
    path: Vec<String>,
    glob: bool,
}

/// Blanks comments, strings and char literals (keeping newlines, so line
/// numbers hold) and drops lifetimes.
fn strip(src: &str) -> String {
    let c: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let ident = |ch: char| ch.is_alphanumeric() || ch == '_';
    let mut i = 0;
    let blank = |out: &mut String, ch: char| out.push(if ch == '\n' { '\n' } else { ' ' });
    while i < c.len() {
        let prev_ident = i > 0 && ident(c[i - 1]);
        if c[i] == '/' && c.get(i + 1) == Some(&'/') {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if c[i] == '/' && c.get(i + 1) == Some(&'*') {
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && c.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if c[i] == '*' && c.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    blank(&mut out, c[i]);
                    i += 1;
                }
            }
        } else if !prev_ident && matches!(c[i], 'r' | 'b' | 'c') && raw_start(&c, i).is_some() {
            let (hashes, body) = raw_start(&c, i).unwrap();
            out.push_str("\"\"");
            i = body;
            while i < c.len() {
                if c[i] == '"' && (0..hashes).all(|k| c.get(i + 1 + k) == Some(&'#')) {
                    i += 1 + hashes;
                    break;
                }
                blank(&mut out, c[i]);
                i += 1;
            }
        } else if c[i] == '"' {
            out.push_str("\"\"");
            i += 1;
            while i < c.len() && c[i] != '"' {
                if c[i] == '\\' {
                    i += 1;
                }
                if i < c.len() {
                    blank(&mut out, c[i]);
                }
                i += 1;
            }
            i += 1;
        } else if c[i] == '\'' {
            if c.get(i + 1) == Some(&'\\') {
                i += 3;
                while i < c.len() && c[i] != '\'' {
                    i += 1;
                }
                i += 1;
                out.push_str("' '");
            } else if c.get(i + 2) == Some(&'\'') {
                i += 3;
                out.push_str("' '");
            } else {
                i += 1;
                while i < c.len() && ident(c[i]) {
                    i += 1;
                }
            }
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// At a raw string (`r"`, `r#"`, `br"`, `cr#"`…): the number of `#` and
/// where its body starts. (`b"…"` is an ordinary string after the `b`.)
fn raw_start(c: &[char], mut i: usize) -> Option<(usize, usize)> {
    if c[i] != 'r' {
        i += 1;
    }
    if c.get(i) != Some(&'r') {
        return None;
    }
    i += 1;
    let mut hashes = 0;
    while c.get(i) == Some(&'#') {
        hashes += 1;
        i += 1;
    }
    (c.get(i) == Some(&'"')).then_some((hashes, i + 1))
}

/// Identifiers, `::` and single punctuation characters, with their lines.
fn tokens(code: &str) -> Vec<(String, usize)> {
    let c: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < c.len() {
        let ch = c[i];
        if ch == '\n' {
            line += 1;
            i += 1;
        } else if ch.is_whitespace() {
            i += 1;
        } else if ch.is_alphanumeric() || ch == '_' {
            let start = i;
            while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                i += 1;
            }
            let word: String = c[start..i].iter().collect();
            if !ch.is_ascii_digit() {
                out.push((word, line));
            }
        } else if ch == ':' && c.get(i + 1) == Some(&':') {
            out.push(("::".into(), line));
            i += 2;
        } else {
            if ch != '$' {
                out.push((ch.to_string(), line));
            }
            i += 1;
        }
    }
    out
}

const ITEM_KEYWORDS: &[&str] = &[
    "fn",
    "struct",
    "enum",
    "trait",
    "type",
    "const",
    "static",
    "union",
    "macro_rules",
];

/// Whether the `mod` at token `i` carries `#[cfg(test)]` or
/// `#[cfg(all(test, …))]` among the attributes before it.
fn cfg_test_before(toks: &[(String, usize)], mut i: usize) -> bool {
    let t = |i: usize| toks[i].0.as_str();
    if i > 0 && t(i - 1) == ")" {
        while i > 0 && t(i - 1) != "(" {
            i -= 1;
        }
        i = i.saturating_sub(1);
    }
    if i > 0 && t(i - 1) == "pub" {
        i -= 1;
    }
    // Each attribute before: `# [ … ]`.
    while i > 0 && t(i - 1) == "]" {
        let end = i - 1;
        let mut start = end;
        while start > 0 && t(start) != "#" {
            start -= 1;
        }
        let inner: Vec<&str> = toks[start + 2..end].iter().map(|t| t.0.as_str()).collect();
        let cfg_test = match inner.as_slice() {
            ["cfg", "(", "test", ")"] => true,
            ["cfg", "(", "all", "(", rest @ ..] => rest.contains(&"test") && !rest.contains(&"not"),
            _ => false,
        };
        if cfg_test {
            return true;
        }
        i = start;
    }
    false
}

fn is_ident(t: &str) -> bool {
    t.chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
}

impl Crate {
    /// Reads every `.rs` file under `root` (the folder of `lib.rs` or
    /// `main.rs`), twice: modules first, then references.
    fn read(root: &Path, label: &str) -> Crate {
        let mut krate = Crate::default();
        let mut paths = Vec::new();
        collect(root, &mut paths);
        paths.sort();
        for path in &paths {
            let rel = path.strip_prefix(root).unwrap();
            let mut module: Module = rel
                .with_extension("")
                .iter()
                .map(|s| s.to_string_lossy().into_owned())
                .collect();
            if matches!(
                module.last().map(String::as_str),
                Some("mod" | "lib" | "main")
            ) {
                module.pop();
            }
            krate.modules.insert(module, krate.files.len());
            krate.files.push(format!("{label}/{}", rel.display()));
        }
        let sources: Vec<String> = paths
            .iter()
            .map(|p| strip(&std::fs::read_to_string(p).unwrap()))
            .collect();
        let file_modules: Vec<Module> = {
            let mut v = vec![Module::new(); paths.len()];
            for (m, &f) in &krate.modules {
                v[f] = m.clone();
            }
            v
        };
        for (file, code) in sources.iter().enumerate() {
            krate.scan(file, file_modules[file].clone(), &tokens(code));
        }
        krate
    }

    /// Walks one file's tokens: inline modules, items, `use` trees and
    /// paths in code.
    fn scan(&mut self, file: usize, top: Module, toks: &[(String, usize)]) {
        let t = |i: usize| toks.get(i).map_or("", |x| x.0.as_str());
        // (module, depth of its body, node its references belong to)
        let mut stack: Vec<(Module, usize, usize)> = vec![(top, 0, file)];
        let mut depth = 0;
        let mut public = false;
        let mut i = 0;
        while i < toks.len() {
            let (here, body, node) = stack.last().unwrap().clone();
            let at_item_level = depth == body;
            match t(i) {
                "{" => depth += 1,
                "}" => {
                    depth -= 1;
                    if depth < stack.last().unwrap().1 {
                        stack.pop();
                    }
                }
                "pub" => {
                    public = true;
                    if t(i + 1) == "(" {
                        while t(i) != ")" {
                            i += 1;
                        }
                    }
                    i += 1;
                    continue;
                }
                "mod" if is_ident(t(i + 1)) && t(i + 2) == "{" => {
                    let mut inner = here.clone();
                    inner.push(t(i + 1).to_string());
                    // An inline test module is a node of its own.
                    let inner_node = if cfg_test_before(toks, i) {
                        self.files
                            .push(format!("{}#{}", self.files[node], t(i + 1)));
                        self.files.len() - 1
                    } else {
                        node
                    };
                    self.modules.insert(inner.clone(), inner_node);
                    depth += 1;
                    stack.push((inner, depth, inner_node));
                    i += 3;
                    public = false;
                    continue;
                }
                "use" => {
                    let line = toks[i].1;
                    let mut entries = Vec::new();
                    i = use_tree(toks, i + 1, Vec::new(), &mut entries);
                    for (path, name, glob) in entries {
                        if glob {
                            self.globs
                                .entry(here.clone())
                                .or_default()
                                .push((path.clone(), public));
                        } else if let Some(name) = name {
                            self.bindings
                                .entry(here.clone())
                                .or_default()
                                .push(Binding {
                                    name,
                                    path: path.clone(),
                                    public,
                                });
                        }
                        self.refs.push(Reference {
                            file: node,
                            module: here.clone(),
                            line,
                            path,
                            glob,
                        });
                    }
                    public = false;
                    continue;
                }
                w if at_item_level && ITEM_KEYWORDS.contains(&w) => {
                    self.defines_items.insert(here.clone());
                }
                w if is_ident(w)
                    && t(i + 1) == "::"
                    && is_ident(t(i + 2))
                    && (i == 0 || t(i - 1) != "::") =>
                {
                    let line = toks[i].1;
                    let mut path = vec![w.to_string()];
                    i += 1;
                    while t(i) == "::" && is_ident(t(i + 1)) {
                        path.push(t(i + 1).to_string());
                        i += 2;
                    }
                    self.refs.push(Reference {
                        file: node,
                        module: here,
                        line,
                        path,
                        glob: false,
                    });
                    public = false;
                    continue;
                }
                _ => {}
            }
            public = false;
            i += 1;
        }
    }

    fn is_module(&self, m: &[String]) -> bool {
        self.modules.contains_key(m)
    }

    /// `path` as written in module `ctx`, made absolute within the crate;
    /// `None` for other crates, local items and generic parameters.
    fn absolute(&self, ctx: &[String], path: &[String], budget: usize) -> Option<Vec<String>> {
        if budget == 0 || path.is_empty() {
            return None;
        }
        let (base, rest): (Vec<String>, &[String]) = match path[0].as_str() {
            "crate" => (Vec::new(), &path[1..]),
            "self" => (ctx.to_vec(), &path[1..]),
            "super" => {
                let mut base = ctx.to_vec();
                let mut k = 0;
                while path.get(k).is_some_and(|s| s == "super") {
                    base.pop()?;
                    k += 1;
                }
                (base, &path[k..])
            }
            first => {
                let mut child = ctx.to_vec();
                child.push(first.to_string());
                if self.is_module(&child) {
                    (ctx.to_vec(), path)
                } else if let Some(b) = self.binding(ctx, first) {
                    let mut base = self.absolute(&b.0, &b.1, budget - 1)?;
                    base.extend_from_slice(&path[1..]);
                    return Some(base);
                } else {
                    // Names brought in by a glob (`use super::*` in tests).
                    let globs = self.globs.get(ctx)?;
                    return globs.iter().find_map(|(g, _)| {
                        let m = self.absolute(ctx, g, budget - 1)?;
                        let mut child = m.clone();
                        child.push(first.to_string());
                        (self.is_module(&child) || self.binding(&m, first).is_some())
                            .then(|| self.absolute(&m, path, budget - 1))?
                    });
                }
            }
        };
        let mut abs = base;
        abs.extend_from_slice(rest);
        Some(abs)
    }

    /// The `use` binding of `name` in module `m`: (its module, raw path).
    fn binding(&self, m: &[String], name: &str) -> Option<(Module, Vec<String>)> {
        let b = self.bindings.get(m)?.iter().find(|b| b.name == name)?;
        Some((m.to_vec(), b.path.clone()))
    }

    /// The file an absolute path resolves to, following re-exports.
    fn resolve(&self, abs: &[String], budget: usize) -> Option<usize> {
        if budget == 0 {
            return None;
        }
        let k = (0..=abs.len()).rev().find(|&k| self.is_module(&abs[..k]))?;
        let module = &abs[..k];
        if k < abs.len() {
            if let Some((ctx, raw)) = self.binding(module, &abs[k]) {
                let mut target = self.absolute(&ctx, &raw, budget - 1)?;
                target.extend_from_slice(&abs[k + 1..]);
                return self.resolve(&target, budget - 1);
            }
        }
        Some(self.modules[module])
    }

    /// Every edge (from file, to file) with the first reference making it.
    fn edges(&self) -> BTreeMap<(usize, usize), String> {
        const BUDGET: usize = 24;
        let mut edges = BTreeMap::new();
        for r in &self.refs {
            let Some(abs) = self.absolute(&r.module, &r.path, BUDGET) else {
                continue;
            };
            let mut targets = Vec::new();
            if r.glob && self.is_module(&abs) {
                if self.defines_items.contains(&abs) {
                    targets.push(self.modules[&abs]);
                }
                for b in self
                    .bindings
                    .get(&abs)
                    .into_iter()
                    .flatten()
                    .filter(|b| b.public)
                {
                    let target = self.absolute(&abs, &b.path, BUDGET);
                    targets.extend(target.and_then(|t| self.resolve(&t, BUDGET)));
                }
            } else {
                targets.extend(self.resolve(&abs, BUDGET));
            }
            for to in targets {
                if to != r.file {
                    let why = format!(
                        "{}:{}: {}{}",
                        self.files[r.file],
                        r.line,
                        r.path.join("::"),
                        if r.glob { "::*" } else { "" }
                    );
                    edges.entry((r.file, to)).or_insert(why);
                }
            }
        }
        edges
    }
}

/// Parses a `use` tree from token `i`, appending (path, bound name, glob)
/// to `out`; returns the index after the tree (after `;` at top level).
fn use_tree(
    toks: &[(String, usize)],
    mut i: usize,
    prefix: Vec<String>,
    out: &mut Vec<(Vec<String>, Option<String>, bool)>,
) -> usize {
    let t = |i: usize| toks.get(i).map_or("", |x| x.0.as_str());
    let mut path = prefix;
    if t(i) == "::" {
        // `use ::other_crate::…`: not this crate.
        path.push("::".into());
        i += 1;
    }
    loop {
        match t(i) {
            "{" => {
                i += 1;
                while t(i) != "}" && i < toks.len() {
                    i = use_tree(toks, i, path.clone(), out);
                    if t(i) == "," {
                        i += 1;
                    }
                }
                i += 1;
                break;
            }
            "*" => {
                out.push((path.clone(), None, true));
                i += 1;
                break;
            }
            w if is_ident(w) => {
                if w != "self" || path.is_empty() {
                    path.push(w.to_string());
                }
                i += 1;
                if t(i) == "::" {
                    i += 1;
                    continue;
                }
                let mut name = path.last().cloned();
                if t(i) == "as" {
                    name = Some(t(i + 1).to_string()).filter(|n| n != "_");
                    i += 2;
                }
                out.push((path.clone(), name, false));
                break;
            }
            _ => break,
        }
    }
    if t(i) == ";" {
        i += 1;
    }
    if path.first().is_some_and(|s| s == "::") {
        out.retain(|(p, _, _)| p.first().is_none_or(|s| s != "::"));
    }
    i
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            collect(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Strongly connected components of more than one node (Tarjan).
fn cycles(n: usize, edges: &BTreeMap<(usize, usize), String>) -> Vec<Vec<usize>> {
    let mut next = vec![Vec::new(); n];
    for &(a, b) in edges.keys() {
        next[a].push(b);
    }
    struct State<'a> {
        next: &'a [Vec<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on: Vec<bool>,
        stack: Vec<usize>,
        counter: usize,
        out: Vec<Vec<usize>>,
    }
    fn visit(s: &mut State, v: usize) {
        s.index[v] = Some(s.counter);
        s.low[v] = s.counter;
        s.counter += 1;
        s.stack.push(v);
        s.on[v] = true;
        for k in 0..s.next[v].len() {
            let w = s.next[v][k];
            match s.index[w] {
                None => {
                    visit(s, w);
                    s.low[v] = s.low[v].min(s.low[w]);
                }
                Some(iw) if s.on[w] => s.low[v] = s.low[v].min(iw),
                _ => {}
            }
        }
        if Some(s.low[v]) == s.index[v] {
            let mut comp = Vec::new();
            loop {
                let w = s.stack.pop().unwrap();
                s.on[w] = false;
                comp.push(w);
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                s.out.push(comp);
            }
        }
    }
    let mut s = State {
        next: &next,
        index: vec![None; n],
        low: vec![0; n],
        on: vec![false; n],
        stack: Vec::new(),
        counter: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if s.index[v].is_none() {
            visit(&mut s, v);
        }
    }
    s.out
}

#[test]
fn no_import_cycles() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
    let mut report = String::new();
    let mut failed = false;
    let mut used = vec![false; ALLOWED_FOR_NOW.len()];
    for label in ["codec/src", "tools/src"] {
        let krate = Crate::read(&repo.join(label), label);
        let edges = krate.edges();
        for comp in cycles(krate.files.len(), &edges) {
            let names: Vec<&str> = comp.iter().map(|&f| krate.files[f].as_str()).collect();
            let allowed = ALLOWED_FOR_NOW
                .iter()
                .position(|set| names.iter().all(|n| set.contains(n)));
            if let Some(k) = allowed {
                used[k] = true;
            }
            failed |= allowed.is_none();
            let verdict = if allowed.is_some() {
                "allowed for now"
            } else {
                "NOT ALLOWED"
            };
            report += &format!("cycle ({verdict}): {}\n", names.join(", "));
            for ((a, b), why) in &edges {
                if comp.contains(a) && comp.contains(b) {
                    report +=
                        &format!("    {} -> {}   ({why})\n", krate.files[*a], krate.files[*b]);
                }
            }
        }
    }
    for (k, set) in ALLOWED_FOR_NOW
        .iter()
        .enumerate()
        .filter(|(k, _)| !used[*k])
    {
        failed = true;
        report += &format!("allowlist entry {k} meets no cycle any more, remove it: {set:?}\n");
    }
    print!("{report}");
    assert!(!failed, "import cycles between files (listed above)");
}

/// The scanner reads code, not comments or strings, and follows
/// re-exports.
#[test]
fn scanner_reads_code_only() {
    let code = strip("let s = \"crate::a::B\"; // crate::c::D\n/* crate::e /* nested */ */ r#\"crate::f\"# 'x' '\\'' 'a crate::g::H");
    let paths: Vec<String> = tokens(&code).into_iter().map(|t| t.0).collect();
    assert_eq!(paths.iter().filter(|t| *t == "crate").count(), 1, "{code}");
    assert!(code.contains("crate::g::H"));
    assert_eq!(code.lines().count(), 2);

    let mut out = Vec::new();
    let toks = tokens("use crate::a::{self, b::{C as D, *}, e};");
    use_tree(&toks, 1, Vec::new(), &mut out);
    let got: Vec<(String, Option<String>, bool)> = out
        .into_iter()
        .map(|(p, n, g)| (p.join("::"), n, g))
        .collect();
    assert_eq!(
        got,
        vec![
            ("crate::a".into(), Some("a".into()), false),
            ("crate::a::b::C".into(), Some("D".into()), false),
            ("crate::a::b".into(), None, true),
            ("crate::a::e".into(), Some("e".into()), false),
        ]
    );
}
