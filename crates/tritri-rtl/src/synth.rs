//! Yosys synthesis of an emitted directory and its resource report.
//!
//! Runs the `synth_generic.ys` / `synth_xilinx.ys` scripts that
//! [`crate::emit`] writes next to the Verilog, and reads Yosys' `stat`
//! output: the generic cell count, and for Xilinx 7-series the LUT, flip-flop,
//! DSP48, carry and shift-register counts.

use crate::tools::{run, ToolError, YOSYS};
use std::collections::BTreeMap;
use std::path::Path;

/// Which synthesis script.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// `synth -flatten`: technology-independent gates.
    Generic,
    /// `synth_xilinx -family xc7`: LUTs, FFs, DSP48E1s.
    Xilinx,
}

impl Target {
    pub fn script(self) -> &'static str {
        match self {
            Target::Generic => "synth_generic.ys",
            Target::Xilinx => "synth_xilinx.ys",
        }
    }
    /// The `stat` report the script writes (`tee -o`).
    pub fn report(self) -> &'static str {
        match self {
            Target::Generic => "stat_generic.txt",
            Target::Xilinx => "stat_xilinx.txt",
        }
    }
}

/// Cell counts from Yosys' `stat` of the flattened top.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ResourceReport {
    /// `Number of cells` of the top.
    pub cells: u64,
    /// Cell type → count.
    pub by_type: BTreeMap<String, u64>,
}

impl ResourceReport {
    fn sum(&self, f: impl Fn(&str) -> bool) -> u64 {
        self.by_type
            .iter()
            .filter(|(k, _)| f(k))
            .map(|(_, v)| v)
            .sum()
    }
    /// LUT1 ... LUT6.
    pub fn luts(&self) -> u64 {
        self.sum(|k| k.starts_with("LUT"))
    }
    /// FDRE, FDSE, FDCE, FDPE (Xilinx) or `$_DFF*` / `$_SDFF*` (generic).
    pub fn flip_flops(&self) -> u64 {
        self.sum(|k| {
            k.starts_with("FD")
                || k.starts_with("$_DFF")
                || k.starts_with("$_SDFF")
                || k.starts_with("$_DFFE")
        })
    }
    /// DSP48E1.
    pub fn dsps(&self) -> u64 {
        self.sum(|k| k.starts_with("DSP48"))
    }
    /// CARRY4.
    pub fn carry_chains(&self) -> u64 {
        self.sum(|k| k.starts_with("CARRY"))
    }
    /// SRL16E / SRLC32E: shift registers in LUTs (delay lines).
    pub fn shift_registers(&self) -> u64 {
        self.sum(|k| k.starts_with("SRL"))
    }
    /// Block RAMs: (RAMB36E1, RAMB18E1).
    pub fn block_rams(&self) -> (u64, u64) {
        (
            self.sum(|k| k.starts_with("RAMB36")),
            self.sum(|k| k.starts_with("RAMB18")),
        )
    }
    /// Distributed RAM: LUTs used as memory (RAM32M, RAM64M, RAM64X1D, ...).
    pub fn distributed_rams(&self) -> u64 {
        self.sum(|k| k.starts_with("RAM") && !k.starts_with("RAMB"))
    }
}

/// Parses the last `stat` report in a Yosys log: the `Number of cells` line
/// and the cell-type lines below it.
pub fn parse_stat(log: &str) -> Option<ResourceReport> {
    let start = log.rfind("Number of cells:")?;
    let mut lines = log[start..].lines();
    let cells = lines.next()?.split(':').nth(1)?.trim().parse().ok()?;
    let mut by_type = BTreeMap::new();
    for line in lines {
        let parts: Vec<&str> = line.split_whitespace().collect();
        match parts.as_slice() {
            [name, count] => {
                if let Ok(n) = count.parse::<u64>() {
                    by_type.insert(name.to_string(), n);
                } else {
                    break;
                }
            }
            [] => {
                if !by_type.is_empty() {
                    break;
                }
            }
            _ => break,
        }
    }
    Some(ResourceReport { cells, by_type })
}

#[derive(Debug, thiserror::Error)]
pub enum SynthError {
    #[error(transparent)]
    Tool(#[from] ToolError),
    #[error("no `stat` report in the Yosys log of {0}")]
    NoReport(String),
}

/// Runs `target`'s script in `dir` (an emitted directory) and returns its report.
pub fn synthesize(dir: &Path, target: Target) -> Result<ResourceReport, SynthError> {
    let report = dir.join(target.report());
    let _ = std::fs::remove_file(&report);
    run(YOSYS
        .command()?
        .current_dir(dir)
        .args(["-q", "-s", target.script()]))?;
    let log = std::fs::read_to_string(&report).unwrap_or_default();
    parse_stat(&log).ok_or_else(|| SynthError::NoReport(report.display().to_string()))
}

/// One row of a resource table.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ResourceRow {
    pub unit: String,
    pub generic: Option<ResourceReport>,
    pub xilinx: Option<ResourceReport>,
}

/// A Markdown table: unit, generic cells, LUTs, FFs, DSP48s, CARRY4s, SRLs,
/// block RAMs (36K + 18K) and distributed RAM cells.
pub fn resource_table(rows: &[ResourceRow]) -> String {
    let mut t = String::from(
        "| unit | generic cells | LUT | FF | DSP48E1 | CARRY4 | SRL | block RAM (36K + 18K) | distributed RAM |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    let cell = |r: &Option<ResourceReport>, f: fn(&ResourceReport) -> u64| {
        r.as_ref().map_or("-".into(), |r| f(r).to_string())
    };
    for r in rows {
        t.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            r.unit,
            cell(&r.generic, |r| r.cells),
            cell(&r.xilinx, ResourceReport::luts),
            cell(&r.xilinx, ResourceReport::flip_flops),
            cell(&r.xilinx, ResourceReport::dsps),
            cell(&r.xilinx, ResourceReport::carry_chains),
            cell(&r.xilinx, ResourceReport::shift_registers),
            r.xilinx.as_ref().map_or("-".into(), |r| {
                let (b36, b18) = r.block_rams();
                format!("{b36} + {b18}")
            }),
            cell(&r.xilinx, ResourceReport::distributed_rams),
        ));
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stat_is_parsed() {
        let log = "=== top ===\n\n   Number of wires:                 10\n   Number of cells:                 7\n     CARRY4                          1\n     FDRE                            3\n     LUT2                            2\n     LUT6                            1\n\nEnd\n";
        let r = parse_stat(log).unwrap();
        assert_eq!(r.cells, 7);
        assert_eq!(
            (r.luts(), r.flip_flops(), r.carry_chains(), r.dsps()),
            (3, 3, 1, 0)
        );
        assert_eq!((r.block_rams(), r.distributed_rams()), ((0, 0), 0));
    }

    #[test]
    fn memories_are_counted_by_kind() {
        let log = "   Number of cells:                 9\n     RAM32M                          2\n     RAM64M                          3\n     RAMB18E1                        1\n     RAMB36E1                        3\n\n";
        let r = parse_stat(log).unwrap();
        assert_eq!(
            (r.block_rams(), r.distributed_rams(), r.luts()),
            ((3, 1), 5, 0)
        );
        let table = resource_table(&[ResourceRow {
            unit: "u".into(),
            generic: None,
            xilinx: Some(r),
        }]);
        assert!(
            table.lines().nth(2).unwrap().ends_with("| 3 + 1 | 5 |"),
            "{table}"
        );
    }
}
