//! The files around the Verilog: per-file headers, `filelist.f`, the FuseSoC
//! core, the Yosys scripts and the README.

use super::modules::{rust_hdl_dff_shape, Module};
use super::{EmittedFile, Port, UnitDescription};

/// Ports of a module, from its `input` / `output` / `inout` declarations
/// (non-ANSI, as rust-hdl prints them, or ANSI).
pub fn top_ports(module: &Module) -> Vec<Port> {
    let words: Vec<&str> = module
        .tokens
        .iter()
        .filter(|t| !t.is_trivia())
        .map(|t| t.text.as_str())
        .collect();
    let mut ports = Vec::new();
    let mut i = 0;
    while i < words.len() {
        if matches!(words[i], "input" | "output" | "inout") {
            let direction = words[i].to_string();
            let mut k = i + 1;
            while k < words.len() && matches!(words[k], "wire" | "reg" | "logic") {
                k += 1;
            }
            let signed = words.get(k) == Some(&"signed");
            if signed {
                k += 1;
            }
            let mut bits = 1;
            if words.get(k) == Some(&"[") {
                let msb: usize = words.get(k + 1).and_then(|w| w.parse().ok()).unwrap_or(0);
                let lsb: usize = words.get(k + 3).and_then(|w| w.parse().ok()).unwrap_or(0);
                bits = msb.abs_diff(lsb) + 1;
                k += 5;
            }
            if let Some(name) = words.get(k) {
                ports.push(Port {
                    name: name.to_string(),
                    direction,
                    bits,
                    signed,
                });
            }
            i = k + 1;
        } else {
            i += 1;
        }
    }
    ports
}

/// rust-hdl path `top$a$b$0` → `a.b[0]` (hierarchy as a Verilog reader writes it).
fn dotted_path(path: &str) -> String {
    let mut out = String::new();
    for (k, seg) in path.split('$').skip(1).enumerate() {
        if seg.chars().all(|c| c.is_ascii_digit()) {
            out.push_str(&format!("[{seg}]"));
        } else {
            if k > 0 {
                out.push('.');
            }
            out.push_str(seg);
        }
    }
    out
}

const RULE: &str =
    "////////////////////////////////////////////////////////////////////////////////";

fn wrap_comment(text: &str, first_prefix: &str, prefix: &str, width: usize) -> String {
    // Headers are ASCII, as the Verilog around them: the units' docs write
    // products and dashes as in print.
    let text = text
        .replace('·', ".")
        .replace('×', " x ")
        .replace(['–', '—'], "-")
        .replace('→', "->");
    let mut lines = Vec::new();
    let mut line = first_prefix.to_string();
    let mut empty = true;
    for word in text.split_whitespace() {
        if !empty && line.len() + 1 + word.len() > width {
            // A comment line that begins with `verilator` is a Verilator
            // directive: such a word takes the one before it along.
            let carried = match line.rsplit_once(' ') {
                Some((rest, last))
                    if word.to_ascii_lowercase().starts_with("verilator")
                        && rest.len() > prefix.len() =>
                {
                    let last = last.to_string();
                    line.truncate(rest.len());
                    Some(last)
                }
                _ => None,
            };
            lines.push(line);
            line = prefix.to_string();
            empty = true;
            if let Some(last) = carried {
                line.push_str(&last);
                empty = false;
            }
        }
        if !empty {
            line.push(' ');
        }
        line.push_str(word);
        empty = false;
    }
    lines.push(line);
    lines.join("\n") + "\n"
}

fn purpose(module: &Module, unit: &UnitDescription, is_top: bool) -> String {
    if is_top {
        let mut text = unit.summary.clone();
        for d in &unit.details {
            text.push(' ');
            text.push_str(d);
        }
        return text;
    }
    let register = rust_hdl_dff_shape(module).is_some()
        || (module.name.starts_with(&format!("{}_dff_", unit.name))
            && module.text().contains("q <= d;"));
    let kind = match module.unit.as_ref().and_then(|u| u.doc()) {
        _ if register => "A D flip-flop register (rust-hdl's DFF) without reset.".to_string(),
        Some(doc) => format!("{} Part of {}.", doc.purpose, unit.name),
        None => format!("Part of {}.", unit.name),
    };
    let count = module.instances.len();
    let shown: Vec<String> = module
        .instances
        .iter()
        .take(4)
        .map(|p| dotted_path(p))
        .collect();
    let instances = match count {
        0 => String::new(),
        1 => format!(" Instance: {}.", shown[0]),
        n if n <= 4 => format!(" Instances ({n}): {}.", shown.join(", ")),
        n => format!(" Instances ({n}), for example: {}.", shown.join(", ")),
    };
    format!("{kind}{instances}")
}

fn header(module: &Module, unit: &UnitDescription, is_top: bool) -> String {
    let mut h = String::new();
    h.push_str(RULE);
    h.push_str("\n//\n");
    h.push_str(&format!("// Filename:   {}.v\n//\n", module.name));
    h.push_str(&wrap_comment(
        &purpose(module, unit, is_top),
        "// Purpose:    ",
        "//             ",
        80,
    ));
    h.push_str("//\n");
    if is_top {
        if !unit.parameters.is_empty() {
            let mut first = true;
            for (name, meaning) in &unit.parameters {
                let lead = if first {
                    "// Parameters: "
                } else {
                    "//             "
                };
                h.push_str(&wrap_comment(
                    &format!("{name} = {meaning}"),
                    lead,
                    "//               ",
                    80,
                ));
                first = false;
            }
            h.push_str("//\n");
        }
        if let Some(l) = unit.latency {
            h.push_str(&format!("// Latency:    {l} clock cycles\n"));
        }
        if !unit.throughput.is_empty() {
            h.push_str(&wrap_comment(
                &unit.throughput,
                "// Throughput: ",
                "//             ",
                80,
            ));
        }
        h.push_str("//\n");
    } else if let Some(u) = &module.unit {
        // The unit's Rust type with its parameters' values: the
        // description this module was generated from.
        h.push_str(&wrap_comment(
            &u.signature(),
            "// Rust unit:  ",
            "//             ",
            80,
        ));
        if let Some(l) = u.latency {
            h.push_str(&format!(
                "// Latency:    {l} clock cycle{}\n",
                if l == 1 { "" } else { "s" }
            ));
        }
        h.push_str("//\n");
    }
    h.push_str(&wrap_comment(
        &format!(
            "Generated by {} from the rust-hdl description; do not edit, regenerate (see README.md).",
            unit.generator
        ),
        "// ",
        "// ",
        80,
    ));
    h.push_str("//\n");
    h.push_str(RULE);
    h.push('\n');
    h
}

/// The text of one module file.
pub fn module_file(module: &Module, unit: &UnitDescription, is_top: bool) -> String {
    let body = module.text();
    // rust-hdl indents and leaves trailing blanks; keep its layout but trim
    // line ends and runs of blank lines.
    let mut lines: Vec<&str> = Vec::new();
    for line in body.lines().map(str::trim_end) {
        if line.is_empty() && lines.last().is_some_and(|l| l.is_empty()) {
            continue;
        }
        lines.push(line);
    }
    format!(
        "{}\n`default_nettype none\n\n{}  // {}\n\n`default_nettype wire\n",
        header(module, unit, is_top),
        lines.join("\n"),
        module.name
    )
}

/// Every file of the emitted directory (see [`super::EmittedDesign::files`]).
/// `models` are simulation models of device primitives the modules
/// instantiate (written as they are, listed first).
pub fn files(
    modules: &[Module],
    ports: &[Port],
    unit: &UnitDescription,
    models: &[EmittedFile],
) -> Vec<EmittedFile> {
    let mut files = Vec::new();
    for (k, m) in modules.iter().enumerate() {
        files.push(EmittedFile {
            path: format!("{}.v", m.name),
            contents: module_file(m, unit, k == 0),
        });
    }
    files.extend(models.iter().cloned());
    // Children first, top last: the order tools that need definitions
    // before use expect.
    let mut order: Vec<String> = models.iter().map(|f| f.path.clone()).collect();
    order.extend(modules.iter().skip(1).map(|m| format!("{}.v", m.name)));
    order.push(format!("{}.v", modules[0].name));
    files.push(EmittedFile {
        path: "filelist.f".into(),
        contents: order.join("\n") + "\n",
    });
    files.push(EmittedFile {
        path: format!("{}.core", unit.name),
        contents: fusesoc_core(&order, unit),
    });
    files.push(EmittedFile {
        path: "synth_generic.ys".into(),
        contents: yosys_script(&order, unit, false),
    });
    files.push(EmittedFile {
        path: "synth_xilinx.ys".into(),
        contents: yosys_script(&order, unit, true),
    });
    files.push(EmittedFile {
        path: "README.md".into(),
        contents: readme(&order, ports, unit),
    });
    files
}

fn fusesoc_core(order: &[String], unit: &UnitDescription) -> String {
    let mut c = String::from("CAPI=2:\n");
    c.push_str(&format!(
        "# Generated by {}; regenerate, do not edit.\n",
        unit.generator
    ));
    c.push_str(&format!(
        "name: {}:{}:{}\n",
        unit.vendor_library,
        unit.name,
        env!("CARGO_PKG_VERSION")
    ));
    c.push_str(&format!(
        "description: \"{}\"\n\n",
        unit.summary.replace('"', "'")
    ));
    c.push_str("filesets:\n  rtl:\n    files:\n");
    for f in order {
        c.push_str(&format!("      - {f}\n"));
    }
    c.push_str("    file_type: verilogSource\n\n");
    c.push_str("targets:\n");
    c.push_str(&format!(
        "  default: &default\n    filesets: [rtl]\n    toplevel: {}\n\n",
        unit.name
    ));
    c.push_str("  lint:\n    <<: *default\n    default_tool: verilator\n    tools:\n      verilator:\n        mode: lint-only\n        verilator_options: [-Wall]\n\n");
    // MULT18X18D and DP16KD instances (`--dsp ecp5`) synthesize for ECP5 only.
    let arch = if order.iter().any(|f| {
        f == super::dsp_mapping::ECP5_MODEL_FILE
            || f == super::block_ram_mapping::ECP5_DP16KD_MODEL_FILE
    }) {
        "ecp5"
    } else {
        "xilinx"
    };
    c.push_str(&format!("  synth:\n    <<: *default\n    default_tool: yosys\n    tools:\n      yosys:\n        arch: {arch}\n"));
    c
}

fn yosys_script(order: &[String], unit: &UnitDescription, xilinx: bool) -> String {
    let mut s = String::new();
    s.push_str(&format!(
        "# Yosys {} synthesis of {} with a resource report; run in this directory:\n#   yosys -q -s {}\n",
        if xilinx { "Xilinx 7-series" } else { "generic" },
        unit.name,
        if xilinx { "synth_xilinx.ys" } else { "synth_generic.ys" }
    ));
    s.push_str(&format!("# Generated by {}.\n", unit.generator));
    for f in order {
        s.push_str(&format!("read_verilog {f}\n"));
    }
    if xilinx {
        s.push_str(&format!("synth_xilinx -top {} -family xc7\n", unit.name));
    } else {
        s.push_str(&format!("synth -flatten -top {}\n", unit.name));
    }
    s.push_str(
        "tee -o stat.txt stat\n"
            .replace(
                "stat.txt",
                if xilinx {
                    "stat_xilinx.txt"
                } else {
                    "stat_generic.txt"
                },
            )
            .as_str(),
    );
    s
}

fn readme(order: &[String], ports: &[Port], unit: &UnitDescription) -> String {
    let mut r = format!("# {}\n\n{}\n\n", unit.name, unit.summary);
    for d in &unit.details {
        r.push_str(d);
        r.push_str("\n\n");
    }
    if !unit.parameters.is_empty() {
        r.push_str("## Parameters\n\n| name | value and meaning |\n|---|---|\n");
        for (n, m) in &unit.parameters {
            r.push_str(&format!("| {n} | {m} |\n"));
        }
        r.push('\n');
    }
    r.push_str("## Ports\n\n| name | direction | width | meaning |\n|---|---|---|---|\n");
    for p in ports {
        let meaning = unit
            .ports
            .iter()
            .find(|(n, _)| n == &p.name)
            .map(|(_, m)| m.as_str())
            .unwrap_or("");
        let width = if p.signed {
            format!("{} (signed)", p.bits)
        } else {
            p.bits.to_string()
        };
        r.push_str(&format!(
            "| `{}` | {} | {} | {} |\n",
            p.name, p.direction, width, meaning
        ));
    }
    r.push_str("\n## Timing\n\n");
    if let Some(l) = unit.latency {
        r.push_str(&format!(
            "- Latency: {l} clock cycles from an input to its result.\n"
        ));
    }
    if !unit.throughput.is_empty() {
        r.push_str(&format!("- Throughput: {}\n", unit.throughput));
    }
    r.push_str("\n## Files\n\n");
    r.push_str(&format!(
        "- `filelist.f`: the {} Verilog-2005 files below, children first, one module per file.\n",
        order.len()
    ));
    r.push_str(&format!(
        "- `{}.core`: FuseSoC (CAPI2) core, targets `default`, `lint`, `synth`.\n",
        unit.name
    ));
    r.push_str(
        "- `synth_generic.ys`, `synth_xilinx.ys`: Yosys synthesis with a `stat` resource report.\n",
    );
    if order
        .iter()
        .any(|f| f == super::dsp_mapping::ECP5_MODEL_FILE)
    {
        r.push_str(&format!(
            "- `{}`: a simulation model of Lattice's MULT18X18D, which the multipliers instantiate with their registers \
             (`tritri gen --dsp ecp5`); Yosys skips it (`SYNTHESIS` is defined), so synthesize with an ECP5 flow \
             (`synth_ecp5`), not the two scripts above.\n",
            super::dsp_mapping::ECP5_MODEL_FILE
        ));
    }
    if order
        .iter()
        .any(|f| f == super::block_ram_mapping::ECP5_DP16KD_MODEL_FILE)
    {
        r.push_str(&format!(
            "- `{}`: a simulation model of Lattice's DP16KD, which the memories with an output register instantiate \
             with both their registers (`tritri gen --dsp ecp5`); Yosys skips it, as above.\n",
            super::block_ram_mapping::ECP5_DP16KD_MODEL_FILE
        ));
    }
    r.push('\n');
    r.push_str("## Use\n\nFrom this directory:\n\n```sh\n");
    r.push_str(&format!(
        "verilator --lint-only -Wall -f filelist.f --top-module {}\n",
        unit.name
    ));
    r.push_str("iverilog -g2012 -c filelist.f -o /dev/null\n");
    r.push_str("yosys -q -s synth_xilinx.ys   # writes stat_xilinx.txt\n```\n\n");
    r.push_str(&format!(
        "Generated by {} (`tritri gen`); do not edit these files, regenerate them.\n",
        unit.generator
    ));
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dotted_paths() {
        assert_eq!(dotted_path("top$a$b$0"), "a.b[0]");
        assert_eq!(dotted_path("top$x"), "x");
    }

    #[test]
    fn comments_wrap_at_width() {
        let text = wrap_comment(
            &"word ".repeat(40),
            "// Purpose:    ",
            "//             ",
            80,
        );
        assert!(text.lines().all(|l| l.len() <= 80), "{text}");
        assert!(text
            .lines()
            .skip(1)
            .all(|l| l.starts_with("//             ")));
    }

    /// No line of a header begins with `verilator` (a directive to Verilator).
    #[test]
    fn no_line_begins_with_verilator() {
        for n in 0..20 {
            let text = format!(
                "{}would look like a loop to Verilator. Part of x.",
                "ab ".repeat(n)
            );
            let wrapped = wrap_comment(&text, "// Purpose:    ", "//             ", 40);
            for line in wrapped.lines() {
                let words = line.trim_start_matches('/').trim_start();
                assert!(
                    !words.to_ascii_lowercase().starts_with("verilator"),
                    "{wrapped}"
                );
            }
        }
    }
}
