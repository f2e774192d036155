//! Splitting rust-hdl's single Verilog string into modules, renaming them
//! after their Rust unit type, and merging modules that rust-hdl printed
//! once per instance although they are the same circuit.
//!
//! rust-hdl names every module after its instance path (`top$stage$reg`) and
//! prints one module per instance, so a design with 300 registers of nine
//! widths has 300 register modules. Identical modules (same text once their
//! own name is blanked out) are merged into one, named after what they are:
//! rust-hdl's `DFF` becomes `<top>_dff_<bits>`, any other module
//! `<top>_<type>` after the Rust type at its instance paths
//! ([`crate::unit`]): `tritri_pipeline_w24_orient3d`. Two circuits of one
//! type are told apart by their widest port (`multiplier_w49`,
//! `multiplier_w74`), else by the parameters they differ in
//! (`delay_line_n3`, `delay_line_n4`).

use super::tokens::{tokenize, untokenize, Kind, Token};
use crate::unit::{UnitInfo, UnitMap};
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// One `module ... endmodule`, as tokens.
#[derive(Clone, Debug)]
pub struct Module {
    pub name: String,
    pub tokens: Vec<Token>,
    /// rust-hdl instance paths (`top$a$b`) this module stands for.
    pub instances: Vec<String>,
    /// The Rust unit type of those instances (none for the top, whose
    /// emitter description says what it is, and for black boxes).
    pub unit: Option<UnitInfo>,
}

impl Module {
    pub fn text(&self) -> String {
        untokenize(&self.tokens)
    }
}

#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ModuleError {
    #[error("rust-hdl output has no module `top`")]
    NoTop,
    #[error("module `{0}` has no `endmodule`")]
    Unterminated(String),
    #[error("in module `{module}`, `{first}` and `{second}` would both be renamed `{renamed}`")]
    NameCollision {
        module: String,
        first: String,
        second: String,
        renamed: String,
    },
    #[error("no unit is recorded at `{0}`: list the field in its parent's `Unit::sub_units`")]
    UnknownUnit(String),
}

/// The modules of `verilog` in order of appearance; text between modules
/// (blank lines, rust-hdl's banner comments, `endmodule // name` trailers) is
/// dropped. An attribute `(* ... *)` right before `module` stays with it.
pub fn split_modules(verilog: &str) -> Result<Vec<Module>, ModuleError> {
    let tokens = tokenize(verilog);
    let mut modules = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        if tokens[i].kind == Kind::Identifier && tokens[i].text == "module" {
            // Keep a preceding attribute.
            let mut start = i;
            let mut j = i;
            while j > 0 && tokens[j - 1].kind == Kind::Whitespace {
                j -= 1;
            }
            if j > 1 && tokens[j - 1].is(")") && tokens[j - 2].is("*") {
                if let Some(open) = (1..j - 2)
                    .rev()
                    .find(|&k| tokens[k].is("*") && tokens[k - 1].is("("))
                {
                    start = open - 1;
                }
            }
            let name = tokens[i + 1..]
                .iter()
                .find(|t| !t.is_trivia())
                .map(|t| t.text.clone())
                .unwrap_or_default();
            let end = (i..tokens.len())
                .find(|&k| tokens[k].kind == Kind::Identifier && tokens[k].text == "endmodule")
                .ok_or_else(|| ModuleError::Unterminated(name.clone()))?;
            modules.push(Module {
                instances: vec![name.clone()],
                name,
                tokens: tokens[start..=end].to_vec(),
                unit: None,
            });
            i = end + 1;
        } else {
            i += 1;
        }
    }
    if !modules.iter().any(|m| m.name == "top") {
        return Err(ModuleError::NoTop);
    }
    Ok(modules)
}

/// `top` → `unit`, `top$a$b` → `unit_a_b`; names rust-hdl did not derive
/// from `top` (black boxes) keep their name, minus any `$`.
pub fn path_name(unit: &str, rust_hdl_name: &str) -> String {
    if rust_hdl_name == "top" {
        unit.to_string()
    } else if let Some(rest) = rust_hdl_name.strip_prefix("top$") {
        format!("{unit}_{}", rest.replace('$', "_"))
    } else {
        rust_hdl_name.replace('$', "_")
    }
}

/// The new name of every identifier of every module: module names from
/// `names`, reserved words get `_kw`, `$` becomes `_`. Where that would merge
/// two identifiers of one module (`base$id`, the port `id` of instance
/// `base`, and a signal `base_id`), the name with `$` uses `__` instead, in
/// every module, so that a port keeps one name in its module and at every
/// instance.
pub fn identifier_names(
    modules: &[Module],
    names: &HashMap<String, String>,
) -> HashMap<String, String> {
    let simple = |name: &str| match names.get(name) {
        Some(n) => n.clone(),
        None if is_reserved_for_renaming(name) => format!("{name}_kw"),
        None => name.replace('$', "_"),
    };
    let mut double: BTreeSet<String> = BTreeSet::new();
    for m in modules {
        let originals: BTreeSet<&str> = m
            .tokens
            .iter()
            .filter(|t| t.kind == Kind::Identifier)
            .map(|t| t.text.as_str())
            .collect();
        let mut by_simple: HashMap<String, Vec<&str>> = HashMap::new();
        for o in &originals {
            by_simple.entry(simple(o)).or_default().push(o);
        }
        for group in by_simple.values().filter(|g| g.len() > 1) {
            for o in group
                .iter()
                .filter(|o| o.contains('$') && !names.contains_key(**o))
            {
                double.insert(o.to_string());
            }
        }
    }
    let mut all = HashMap::new();
    for m in modules {
        for t in m.tokens.iter().filter(|t| t.kind == Kind::Identifier) {
            if !all.contains_key(&t.text) {
                let new = if double.contains(&t.text) {
                    t.text.replace('$', "__")
                } else {
                    simple(&t.text)
                };
                all.insert(t.text.clone(), new);
            }
        }
    }
    all
}

/// Renames every identifier of `module` by `renamed` (from
/// [`identifier_names`]); refuses a rename that merges two identifiers.
pub fn rename_identifiers(
    module: &mut Module,
    renamed: &HashMap<String, String>,
) -> Result<(), ModuleError> {
    let mut renamed_from: HashMap<&str, &str> = HashMap::new();
    for t in module.tokens.iter().filter(|t| t.kind == Kind::Identifier) {
        let new = renamed[&t.text].as_str();
        if let Some(previous) = renamed_from.insert(new, t.text.as_str()) {
            if previous != t.text {
                return Err(ModuleError::NameCollision {
                    module: module.name.clone(),
                    first: previous.to_string(),
                    second: t.text.clone(),
                    renamed: new.to_string(),
                });
            }
        }
    }
    for token in module
        .tokens
        .iter_mut()
        .filter(|t| t.kind == Kind::Identifier)
    {
        token.text = renamed[&token.text].clone();
    }
    if let Some(n) = renamed.get(&module.name) {
        module.name = n.clone();
    }
    Ok(())
}

/// A register field named `x_q` (the lowRISC name of a register's output)
/// would come out as `x_q_q`, `x_q_d` and `x_q_clock`: rust-hdl names the
/// nets of instance `x_q` after its ports. They become `x_q`, `x_d` and
/// `x_clock`, and the instance `u_x_q`. `registers` are the names of the
/// register modules. A register whose new names are taken keeps rust-hdl's.
pub fn name_register_nets(module: &mut Module, registers: &BTreeSet<String>) {
    let taken: BTreeSet<String> = module
        .tokens
        .iter()
        .filter(|t| t.kind == Kind::Identifier)
        .map(|t| t.text.clone())
        .collect();
    let significant: Vec<usize> = module
        .tokens
        .iter()
        .enumerate()
        .filter(|(_, t)| !t.is_trivia())
        .map(|(i, _)| i)
        .collect();
    let mut renamed: HashMap<String, String> = HashMap::new();
    for w in significant.windows(3) {
        let (kind, instance, open) = (
            &module.tokens[w[0]],
            &module.tokens[w[1]],
            &module.tokens[w[2]],
        );
        if kind.kind != Kind::Identifier || !registers.contains(&kind.text) || !open.is("(") {
            continue;
        }
        let Some(stem) = instance.text.strip_suffix("_q") else {
            continue;
        };
        let new: Vec<(String, String)> = vec![
            (instance.text.clone(), format!("u_{}", instance.text)),
            (format!("{}$q", instance.text), instance.text.clone()),
            (format!("{}$d", instance.text), format!("{stem}_d")),
            (format!("{}$clock", instance.text), format!("{stem}_clock")),
        ];
        // `x_q` itself is taken by the instance, which is renamed.
        if new
            .iter()
            .filter(|(_, to)| *to != instance.text)
            .all(|(_, to)| !taken.contains(to))
        {
            renamed.extend(new);
        }
    }
    for token in module
        .tokens
        .iter_mut()
        .filter(|t| t.kind == Kind::Identifier)
    {
        if let Some(n) = renamed.get(&token.text) {
            token.text = n.clone();
        }
    }
}

/// Instance names get the prefix `u_` (lowRISC style). rust-hdl names an
/// instance after its field, which is often also the name of one of the
/// child's ports (`axis`), and Verilator warns that the port hides the
/// instance (VARHIDDEN). Instances are referred to only where they are
/// declared (rust-hdl connects them through stub nets), so the rename is
/// local. A name already taken keeps its original; a name that already has
/// the prefix ([`name_register_nets`]) keeps it once.
pub fn prefix_instance_names(module: &mut Module, module_names: &BTreeSet<String>) {
    let taken: BTreeSet<String> = module
        .tokens
        .iter()
        .filter(|t| t.kind == Kind::Identifier)
        .map(|t| t.text.clone())
        .collect();
    let significant: Vec<usize> = module
        .tokens
        .iter()
        .enumerate()
        .filter(|(_, t)| !t.is_trivia())
        .map(|(i, _)| i)
        .collect();
    for w in significant.windows(3) {
        let (kind, instance, open) = (
            &module.tokens[w[0]],
            &module.tokens[w[1]],
            &module.tokens[w[2]],
        );
        if kind.kind == Kind::Identifier
            && module_names.contains(&kind.text)
            && kind.text != module.name
            && instance.kind == Kind::Identifier
            && open.is("(")
        {
            let new = format!("u_{}", instance.text);
            if !instance.text.starts_with("u_") && !taken.contains(&new) {
                module.tokens[w[1]].text = new;
            }
        }
    }
}

/// Words that are reserved in SystemVerilog (which Verilator and
/// `iverilog -g2012` parse `.v` files as) or in Verilog's UDP and
/// configuration syntax, but that rust-hdl accepts as field names: a field
/// `table` or `cross` would be a syntax error. They get the suffix `_kw`.
/// Keywords that rust-hdl's generated code and Verilog-2005 custom code use
/// as keywords are not in the list.
fn is_reserved_for_renaming(name: &str) -> bool {
    const WORDS: &[&str] = &[
        "alias",
        "always_comb",
        "always_ff",
        "always_latch",
        "assert",
        "assume",
        "before",
        "bind",
        "bins",
        "binsof",
        "bit",
        "break",
        "byte",
        "cell",
        "chandle",
        "checker",
        "class",
        "clocking",
        "config",
        "const",
        "constraint",
        "context",
        "continue",
        "cover",
        "covergroup",
        "coverpoint",
        "cross",
        "design",
        "dist",
        "do",
        "endchecker",
        "endclass",
        "endclocking",
        "endconfig",
        "endgroup",
        "endinterface",
        "endpackage",
        "endprimitive",
        "endprogram",
        "endproperty",
        "endsequence",
        "endtable",
        "enum",
        "eventually",
        "expect",
        "export",
        "extends",
        "extern",
        "final",
        "first_match",
        "foreach",
        "forkjoin",
        "global",
        "iff",
        "ignore_bins",
        "illegal_bins",
        "implements",
        "implies",
        "import",
        "incdir",
        "include",
        "inside",
        "instance",
        "int",
        "interconnect",
        "interface",
        "intersect",
        "join_any",
        "join_none",
        "let",
        "liblist",
        "library",
        "local",
        "logic",
        "longint",
        "matches",
        "modport",
        "nettype",
        "new",
        "nexttime",
        "null",
        "package",
        "packed",
        "primitive",
        "priority",
        "program",
        "property",
        "protected",
        "pure",
        "rand",
        "randc",
        "randcase",
        "randsequence",
        "ref",
        "restrict",
        "return",
        "sequence",
        "shortint",
        "shortreal",
        "showcancelled",
        "soft",
        "solve",
        "static",
        "string",
        "strong",
        "struct",
        "super",
        "sync_accept_on",
        "sync_reject_on",
        "table",
        "tagged",
        "this",
        "throughout",
        "timeprecision",
        "timeunit",
        "type",
        "typedef",
        "union",
        "unique",
        "unique0",
        "until",
        "untyped",
        "use",
        "var",
        "virtual",
        "void",
        "wait_order",
        "weak",
        "wildcard",
        "with",
        "within",
    ];
    WORDS.contains(&name)
}

/// The shape of rust-hdl's `DFF<T>`: ports `d`, `q`, `clock` and the body
/// `initial q = <default>; always @(posedge clock) q <= d;`.
/// Returns (bits, signed) when `module` is one.
pub fn rust_hdl_dff_shape(module: &Module) -> Option<(usize, bool)> {
    let words: Vec<&str> = module
        .tokens
        .iter()
        .filter(|t| !t.is_trivia())
        .map(|t| t.text.as_str())
        .collect();
    let header = ["module", "?", "(", "d", ",", "q", ",", "clock", ")", ";"];
    if words.len() < header.len() || words[0] != "module" || words[2..header.len()] != header[2..] {
        return None;
    }
    let rest = &words[header.len()..];
    // input wire [signed] [[N:0]] d ; output reg ... q ; input wire clock ;
    let (d, after_d) = port_declaration(rest, "input", "wire", "d")?;
    let (q, after_q) = port_declaration(after_d, "output", "reg", "q")?;
    let (clock, after_clock) = port_declaration(after_q, "input", "wire", "clock")?;
    if d != q || clock != (1, false) {
        return None;
    }
    // Optional enum localparams (rust-hdl copies a state enum's labels into
    // its register), then the fixed body.
    let mut body = after_clock;
    while body.first() == Some(&"localparam") {
        let end = body.iter().position(|w| *w == ";")?;
        body = &body[end + 1..];
    }
    let expected = [
        "initial",
        "begin",
        "q",
        "=",
        "?",
        ";",
        "end",
        "always",
        "@",
        "(",
        "posedge",
        "clock",
        ")",
        "begin",
        "q",
        "<=",
        "d",
        ";",
        "end",
        "endmodule",
    ];
    if body.len() != expected.len() || body.iter().zip(expected).any(|(w, e)| e != "?" && *w != e) {
        return None;
    }
    Some(d)
}

/// `direction kind [signed] [[N:0]] name ;` → ((bits, signed), rest).
fn port_declaration<'a, 'b>(
    words: &'a [&'b str],
    direction: &str,
    kind: &str,
    name: &str,
) -> Option<((usize, bool), &'a [&'b str])> {
    if words.len() < 4 || words[0] != direction || words[1] != kind {
        return None;
    }
    let mut k = 2;
    let signed = words[k] == "signed";
    if signed {
        k += 1;
    }
    let mut bits = 1;
    if words[k] == "[" {
        if words.len() < k + 6 || words[k + 2] != ":" || words[k + 3] != "0" || words[k + 4] != "]"
        {
            return None;
        }
        bits = words[k + 1].parse::<usize>().ok()? + 1;
        k += 5;
    }
    if words.get(k) != Some(&name) || words.get(k + 1) != Some(&";") {
        return None;
    }
    Some(((bits, signed), &words[k + 2..]))
}

/// A clean register module in place of rust-hdl's `DFF` text: ANSI ports,
/// and a power-on value of the right width (rust-hdl writes `64'h0` for a
/// one-bit enum register, a width warning).
pub fn dff_module(name: &str, bits: usize, signed: bool) -> Module {
    let range = if bits == 1 {
        String::new()
    } else {
        format!(" [{}:0]", bits - 1)
    };
    let sign = if signed { " signed" } else { "" };
    let text = format!(
        "module {name} (\n    input  wire{sign}{range} d,\n    output reg {sign}{range} q,\n    input  wire clock\n);\n\n    \
         // Power-on value, as in the rust-hdl simulation; FPGA flows keep it.\n    \
         initial q = {bits}'d0;\n\n    \
         always @(posedge clock) begin\n        q <= d;\n    end\n\nendmodule"
    );
    Module {
        name: name.to_string(),
        tokens: tokenize(&text),
        instances: Vec::new(),
        unit: None,
    }
}

/// The text of `module` with its own name blanked out: two modules with the
/// same key are the same circuit.
fn structure_key(module: &Module) -> String {
    module
        .tokens
        .iter()
        .filter(|t| t.kind != Kind::Comment)
        .map(|t| {
            if t.kind == Kind::Identifier && t.text == module.name {
                "\u{0}"
            } else {
                t.text.as_str()
            }
        })
        .collect()
}

/// Splits, renames and merges: the result has the top first (named `unit`),
/// then the other modules by name, no `$` in any identifier, and no two
/// modules with the same text. `units` gives the Rust type at each instance
/// path.
pub fn normalize(verilog: &str, unit: &str, units: &UnitMap) -> Result<Vec<Module>, ModuleError> {
    let mut modules = split_modules(verilog)?;
    // Merge identical modules bottom-up: a parent's text names its children,
    // so children are merged (and renamed in the parents) first. Modules are
    // taken by height (0: no submodules; else 1 + the children's maximum),
    // and identical modules have the same height, wherever they sit.
    let heights = module_heights(&modules);
    let max_height = heights.values().copied().max().unwrap_or(0);
    // Each group first gets a placeholder name `group$<n>`; the final names
    // are chosen once every group is known, so that two groups that would
    // get the same name are told apart the same way.
    let mut desired: BTreeMap<String, (String, Option<(usize, bool)>)> = BTreeMap::new();
    let mut group_count = 0;
    for level in 0..=max_height {
        // Group this level's modules by structure.
        let mut groups: BTreeMap<String, Vec<usize>> = BTreeMap::new();
        for (i, m) in modules.iter().enumerate() {
            if heights.get(&m.instances[0]) == Some(&level) && m.name.starts_with("top$") {
                groups.entry(structure_key(m)).or_default().push(i);
            }
        }
        let mut group_list: Vec<Vec<usize>> = groups.into_values().collect();
        group_list.sort_by_key(|g| modules[g[0]].name.clone());
        let mut renames: HashMap<String, String> = HashMap::new();
        for group in group_list {
            let members: Vec<String> = group.iter().map(|&i| modules[i].name.clone()).collect();
            let dff = rust_hdl_dff_shape(&modules[group[0]]);
            let info = units
                .get(&members[0])
                .ok_or_else(|| ModuleError::UnknownUnit(members[0].clone()))?
                .clone();
            let name = if let Some((bits, signed)) = dff {
                format!("{unit}_dff_{}{bits}", if signed { "signed_" } else { "" })
            } else {
                format!("{unit}_{}", info.module_stem())
            };
            let placeholder = format!("group${group_count}");
            group_count += 1;
            desired.insert(placeholder.clone(), (name, dff));
            for &i in &group {
                modules[i].unit = Some(info.clone());
            }
            for m in &members {
                renames.insert(m.to_string(), placeholder.clone());
            }
        }
        // Rename this level's names inside every module (parents refer to them).
        for m in modules.iter_mut() {
            for t in m.tokens.iter_mut().filter(|t| t.kind == Kind::Identifier) {
                if let Some(n) = renames.get(&t.text) {
                    t.text = n.clone();
                }
            }
            if let Some(n) = renames.get(&m.name) {
                m.name = n.clone();
            }
        }
        // Keep one module per name, with the instances of all.
        let mut instances: BTreeMap<String, Vec<String>> = BTreeMap::new();
        for m in &modules {
            instances
                .entry(m.name.clone())
                .or_default()
                .extend(m.instances.iter().cloned());
        }
        let mut seen = BTreeSet::new();
        modules.retain(|m| seen.insert(m.name.clone()));
        for m in modules.iter_mut() {
            m.instances = instances.remove(&m.name).unwrap_or_default();
        }
    }
    // Final names. Registers of one width share one name by construction
    // (enum registers differ only in their labels, dropped by dff_module).
    // Other names wanted by several groups get the width of the group's
    // widest port (`multiplier_w49`, `multiplier_w74`) where that tells them
    // apart, else the parameters they differ in, then a number.
    let mut wanted: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (placeholder, (name, dff)) in &desired {
        if dff.is_none() {
            wanted
                .entry(name.clone())
                .or_default()
                .push(placeholder.clone());
        }
    }
    let module = |placeholder: &str| modules.iter().find(|m| m.name == placeholder);
    let widest = |placeholder: &str| {
        module(placeholder)
            .map(|m| {
                super::package::top_ports(m)
                    .iter()
                    .map(|p| p.bits)
                    .max()
                    .unwrap_or(1)
            })
            .unwrap_or(1)
    };
    let mut final_names: HashMap<String, String> = HashMap::new();
    let mut taken: BTreeSet<String> = BTreeSet::new();
    taken.insert(unit.to_string());
    for (placeholder, (name, dff)) in &desired {
        if dff.is_some() {
            final_names.insert(placeholder.clone(), name.clone());
            taken.insert(name.clone());
        }
    }
    for (name, placeholders) in &wanted {
        let widths: BTreeSet<usize> = placeholders.iter().map(|p| widest(p)).collect();
        let infos: Vec<&UnitInfo> = placeholders
            .iter()
            .filter_map(|p| module(p)?.unit.as_ref())
            .collect();
        for (p, info) in placeholders.iter().zip(&infos) {
            let mut candidate = if placeholders.len() == 1 {
                name.clone()
            } else if widths.len() == placeholders.len() {
                format!("{name}_w{}", widest(p))
            } else {
                format!("{name}{}", parameter_suffix(info, &infos))
            };
            if taken.contains(&candidate) {
                let stem = candidate.clone();
                candidate = (2..)
                    .map(|k| format!("{stem}_{k}"))
                    .find(|n| !taken.contains(n))
                    .unwrap();
            }
            taken.insert(candidate.clone());
            final_names.insert(p.clone(), candidate);
        }
    }
    for m in modules.iter_mut() {
        for t in m.tokens.iter_mut().filter(|t| t.kind == Kind::Identifier) {
            if let Some(n) = final_names.get(&t.text) {
                t.text = n.clone();
            }
        }
        if let Some(n) = final_names.get(&m.name) {
            m.name = n.clone();
        }
    }
    // Registers of one width from several groups (enum registers) are now
    // duplicates by name: keep one, with every instance.
    let mut instances: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for m in &modules {
        instances
            .entry(m.name.clone())
            .or_default()
            .extend(m.instances.iter().cloned());
    }
    let mut seen = BTreeSet::new();
    modules.retain(|m| seen.insert(m.name.clone()));
    for m in modules.iter_mut() {
        m.instances = instances.remove(&m.name).unwrap_or_default();
    }
    let mut names: HashMap<String, String> = HashMap::new();
    for m in &modules {
        names.insert(m.name.clone(), path_name(unit, &m.name));
    }
    let mut registers: BTreeSet<String> = BTreeSet::new();
    for m in modules.iter_mut() {
        if let Some((bits, signed)) = rust_hdl_dff_shape(m) {
            let instances = std::mem::take(&mut m.instances);
            *m = dff_module(&m.name, bits, signed);
            m.instances = instances;
            registers.insert(m.name.clone());
        }
    }
    for m in modules.iter_mut() {
        name_register_nets(m, &registers);
    }
    let renamed = identifier_names(&modules, &names);
    let mut result = Vec::new();
    for mut m in modules {
        rename_identifiers(&mut m, &renamed)?;
        result.push(m);
    }
    let module_names: BTreeSet<String> = result.iter().map(|m| m.name.clone()).collect();
    for m in result.iter_mut() {
        prefix_instance_names(m, &module_names);
    }
    result.sort_by(|a, b| (a.name != unit, &a.name).cmp(&(b.name != unit, &b.name)));
    Ok(result)
}

/// Height of every module (by its rust-hdl name): 0 without submodules,
/// else one more than its tallest child.
fn module_heights(modules: &[Module]) -> HashMap<String, usize> {
    let names: BTreeSet<&str> = modules.iter().map(|m| m.name.as_str()).collect();
    let children: HashMap<&str, Vec<&str>> = modules
        .iter()
        .map(|m| {
            // A child is a module name in instantiation position: followed
            // by the instance's name. (A signal may share a module's name:
            // the binning unit's register `top` inside the broad-phase top,
            // itself `top` in rust-hdl's text.)
            let significant: Vec<&Token> = m
                .tokens
                .iter()
                .filter(|t| !matches!(t.kind, Kind::Whitespace | Kind::Comment))
                .collect();
            let kids = significant
                .windows(2)
                .filter(|w| {
                    w[0].kind == Kind::Identifier
                        && w[0].text != m.name
                        && names.contains(w[0].text.as_str())
                        && matches!(w[1].kind, Kind::Identifier | Kind::EscapedIdentifier)
                })
                .map(|w| w[0].text.as_str())
                .collect();
            (m.name.as_str(), kids)
        })
        .collect();
    fn height<'a>(
        n: &'a str,
        children: &HashMap<&'a str, Vec<&'a str>>,
        memo: &mut HashMap<String, usize>,
    ) -> usize {
        if let Some(&h) = memo.get(n) {
            return h;
        }
        let h = children
            .get(n)
            .map(|kids| {
                kids.iter()
                    .map(|k| height(k, children, memo) + 1)
                    .max()
                    .unwrap_or(0)
            })
            .unwrap_or(0);
        memo.insert(n.to_string(), h);
        h
    }
    let mut memo = HashMap::new();
    for m in modules {
        height(&m.name, &children, &mut memo);
    }
    memo
}

/// `_n4` for a `DelayLine<Bits<25>, 4>` among delay lines of other lengths:
/// the parameters in which `info` differs from any of `group`, a number as
/// its name and value (`n4`, `depth512`), a signal type as its width
/// (`w25`), another type by its name (`cell_lists`).
fn parameter_suffix(info: &UnitInfo, group: &[&UnitInfo]) -> String {
    let mut suffix = String::new();
    for (i, (name, value)) in info.parameters.iter().enumerate() {
        if group
            .iter()
            .all(|g| g.parameters.get(i).map(|(_, v)| v) == Some(value))
        {
            continue;
        }
        let bits = value
            .strip_prefix("Bits<")
            .or_else(|| value.strip_prefix("Signed<"));
        let part = match bits {
            // A signal type is named by its width, as ports are.
            Some(bits) => format!("w{}", bits.trim_end_matches('>')),
            None if value == "bool" => "w1".to_string(),
            None if value.starts_with(|c: char| c.is_ascii_digit()) => {
                format!("{}{value}", name.to_ascii_lowercase())
            }
            None => UnitInfo {
                type_name: value.clone(),
                parameters: Vec::new(),
                latency: None,
            }
            .module_stem(),
        };
        suffix.push('_');
        suffix.push_str(&part);
    }
    suffix
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = "\n\nmodule top(clock,a$x,y);\n    input wire clock;\n    input wire [7:0] a$x;\n    output reg [8:0] y;\n    wire [8:0] r$q;\n    top$r r(\n.clock(clock),\n.d(r$d),\n.q(r$q)\n);\nendmodule // top\n\n\nmodule top$r(d,q,clock);\n    \n    // Module arguments\n    input wire  [8:0] d;\n    output reg  [8:0] q;\n    input wire  clock;\n    \n    // Update code (custom)\n    initial begin\n       q = 9'h0;\n    end\n    \n    always @(posedge clock) begin\n       q <= d;\n    end\n          \nendmodule // top$r\n";

    /// The sample's units: its register at `top$<name>`.
    fn register_at(name: &str) -> UnitMap {
        let info = UnitInfo::of(&rust_hdl::prelude::DFF::<rust_hdl::prelude::Bits<9>>::default());
        UnitMap::from([(format!("top${name}"), info)])
    }

    /// The sample splits into its two modules, the register is recognized.
    #[test]
    fn split_and_recognize_dff() {
        let modules = split_modules(SAMPLE).unwrap();
        assert_eq!(
            modules.iter().map(|m| m.name.as_str()).collect::<Vec<_>>(),
            vec!["top", "top$r"]
        );
        assert_eq!(rust_hdl_dff_shape(&modules[1]), Some((9, false)));
        assert_eq!(rust_hdl_dff_shape(&modules[0]), None);
    }

    /// Renaming leaves no `$` and names the register by its width.
    #[test]
    fn normalize_renames_everything() {
        let modules = normalize(SAMPLE, "unit_w8", &register_at("r")).unwrap();
        let names: Vec<_> = modules.iter().map(|m| m.name.clone()).collect();
        assert_eq!(names, vec!["unit_w8", "unit_w8_dff_9"]);
        for m in &modules {
            let text = m.text();
            assert!(!text.contains('$'), "{text}");
        }
        assert!(modules[0].text().contains("unit_w8_dff_9 u_r("));
        assert!(modules[0].text().contains("a_x"));
    }

    /// `a$b` next to `a_b` becomes `a__b`; `a$b` next to `a_b` and `a__b` is refused.
    #[test]
    fn collisions_use_double_underscore_or_are_refused() {
        let text = "module top(a$b, a_b);\ninput wire a$b;\noutput wire a_b;\nendmodule\n";
        let m = normalize(text, "u", &UnitMap::new()).unwrap();
        assert!(m[0].text().contains("input wire a__b;"), "{}", m[0].text());
        let text = "module top(a$b, a_b, a__b);\ninput wire a$b;\noutput wire a_b;\noutput wire a__b;\nendmodule\n";
        assert!(matches!(
            normalize(text, "u", &UnitMap::new()),
            Err(ModuleError::NameCollision { .. })
        ));
    }

    /// A register field `r_q` gives nets `r_q` and `r_d`, not `r_q_q` and
    /// `r_q_d`; a register whose new names are taken keeps rust-hdl's.
    #[test]
    fn register_outputs_are_named_q_once() {
        let text = SAMPLE.replace("r$", "r_q$").replace(" r(", " r_q(");
        let modules = normalize(&text, "unit_w8", &register_at("r")).unwrap();
        let top = modules[0].text();
        assert!(top.contains("unit_w8_dff_9 u_r_q("), "{top}");
        assert!(top.contains(".d(r_d)") && top.contains(".q(r_q)"), "{top}");
        assert!(!top.contains("r_q_q") && !top.contains("r_q_d"), "{top}");
        let taken = text.replace("output reg [8:0] y;", "output reg [8:0] y;\n    wire r_d;");
        let top = normalize(&taken, "unit_w8", &register_at("r")).unwrap()[0].text();
        assert!(top.contains(".q(r_q_q)"), "{top}");
    }
}
