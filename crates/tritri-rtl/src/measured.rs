//! What synthesis and place-and-route measured on the emitted designs,
//! kept in `rtl-out/measurements.json` (the machine-readable form of
//! `rtl-out/README.md`'s tables; a test holds the two equal) and built into
//! the program, so that `tritri report` and `tritri gen --for-scene` read
//! measured figures without running Yosys or nextpnr again.

use crate::pipeline::pipeline_unit::pipeline_unit_name_for;
use crate::pipeline::RareCasePath;
use serde::{Deserialize, Serialize};

/// The committed measurements (`rtl-out/measurements.json`).
pub const COMMITTED: &str = include_str!("../../../rtl-out/measurements.json");

/// Every measured design.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Measurements {
    /// Where the figures come from (free text, for the reader of the file).
    pub about: String,
    /// The day of the last measurement.
    pub measured: String,
    /// The flows' tools and versions, by flow name.
    pub tools: std::collections::BTreeMap<String, String>,
    pub xilinx: Vec<XilinxRow>,
    pub ecp5: Vec<Ecp5Row>,
}

/// `tritri gen --synth xilinx` (and `generic`) on one top.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct XilinxRow {
    pub unit: String,
    /// Yosys' generic cells (`--synth generic`), where measured.
    pub generic_cells: Option<u64>,
    pub lut: u64,
    pub ff: u64,
    pub dsp48e1: u64,
    pub carry4: u64,
    pub srl: u64,
    /// Block RAMs, where the table has the column.
    pub ramb36: Option<u64>,
    pub ramb18: Option<u64>,
    pub distributed_ram: Option<u64>,
}

/// `tritri gen --synth ecp5` on one top: post-route.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Ecp5Row {
    pub unit: String,
    pub fmax_mhz: f64,
    /// nextpnr's placement seed: the same netlist routes a few per cent
    /// faster or slower with another (files without it: seed 1, the flow's).
    #[serde(default = "first_seed")]
    pub seed: u64,
    pub lut4: u64,
    pub ff: u64,
    pub mult18x18d: u64,
    pub ebr: u64,
}

fn first_seed() -> u64 {
    1
}

impl Measurements {
    /// The measurements built into the program.
    pub fn committed() -> Measurements {
        serde_json::from_str(COMMITTED)
            .expect("rtl-out/measurements.json is checked by the test `measurements_parse`")
    }

    /// Measurements from a file of the same shape (a user's own runs);
    /// every post-route clock must be a positive number of MHz.
    pub fn parse(json: &str) -> Result<Measurements, String> {
        let m: Measurements = serde_json::from_str(json).map_err(|e| e.to_string())?;
        if let Some(r) = m
            .ecp5
            .iter()
            .find(|r| !(r.fmax_mhz.is_finite() && r.fmax_mhz > 0.0))
        {
            return Err(format!(
                "{}: fmax_mhz {} is not a positive clock",
                r.unit, r.fmax_mhz
            ));
        }
        Ok(m)
    }

    /// The Xilinx row of `unit`.
    pub fn xilinx(&self, unit: &str) -> Option<&XilinxRow> {
        self.xilinx.iter().find(|r| r.unit == unit)
    }

    /// The ECP5 row of `unit`.
    pub fn ecp5(&self, unit: &str) -> Option<&Ecp5Row> {
        self.ecp5.iter().find(|r| r.unit == unit)
    }

    /// The `width`-bit pipeline routed on ECP5, and where it tests its rare
    /// pairs: the parallel units (the default, which never stalls) where
    /// that pipeline was routed, else the shared unit (for widths whose
    /// parallel units do not route at the clock, such as W = 16:
    /// rtl-out/README.md). Its stall cost is the scene's; those who run a
    /// scene on it count it ([`crate::system::rare_case_model`]).
    pub fn ecp5_pipeline(&self, width: u32) -> Option<(RareCasePath, &Ecp5Row)> {
        RareCasePath::ALL.into_iter().find_map(|path| {
            let row = self.ecp5(&pipeline_unit_name_for(width as usize, path))?;
            Some((path, row))
        })
    }
}

/// A part a design is sized for: its resource budget, written once.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Device {
    /// The name users give (`--device`).
    pub name: &'static str,
    pub part: &'static str,
    /// The flow whose measurements apply: `ecp5` or `xilinx`.
    pub flow: &'static str,
    pub luts: u64,
    pub flip_flops: u64,
    /// 18 x 18 multipliers (MULT18X18D) or DSP48E1 slices.
    pub dsps: u64,
    /// 18-kbit block RAMs (EBR, or RAMB18 halves of the RAMB36s).
    pub block_rams_18k: u64,
}

/// The devices `tritri` sizes designs for (vendors' data sheets).
pub const DEVICES: [Device; 2] = [
    Device {
        name: "ecp5-85",
        part: "LFE5U-85F",
        flow: "ecp5",
        luts: 83_640,
        flip_flops: 83_640,
        dsps: 156,
        block_rams_18k: 208,
    },
    Device {
        name: "artix7-200t",
        part: "XC7A200T",
        flow: "xilinx",
        luts: 133_800,
        flip_flops: 267_600,
        dsps: 740,
        block_rams_18k: 730,
    },
];

/// The device called `name`.
pub fn device(name: &str) -> Option<&'static Device> {
    DEVICES.iter().find(|d| d.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn measurements_parse() {
        let m = Measurements::committed();
        assert_eq!(Measurements::parse(COMMITTED), Ok(m.clone()));
        // The first ECP5 row's clock, whatever it is, set to zero.
        let first = m.ecp5("tritri_pipeline_w8").unwrap().fmax_mhz;
        let stopped = COMMITTED.replacen(&format!("\"fmax_mhz\": {first}"), "\"fmax_mhz\": 0.0", 1);
        assert!(Measurements::parse(&stopped)
            .unwrap_err()
            .contains("tritri_pipeline_w8: fmax_mhz 0 is not a positive clock"));
        assert!(m.xilinx("tritri_pipeline_w24").is_some());
        assert!(m.ecp5("tritri_pipeline_w8").is_some());
    }

    #[test]
    fn the_routed_pipeline_of_a_width_is_parallel_where_routed_else_shared() {
        let mut m = Measurements::committed();
        let row = |unit: &str| Ecp5Row {
            unit: unit.into(),
            fmax_mhz: 100.0,
            seed: 1,
            lut4: 1,
            ff: 1,
            mult18x18d: 1,
            ebr: 0,
        };
        m.ecp5 = vec![
            row("tritri_pipeline_shared_w16"),
            row("tritri_pipeline_w8"),
            row("tritri_pipeline_shared_w8"),
        ];
        let path = |w| m.ecp5_pipeline(w).map(|(p, r)| (p, r.unit.clone()));
        assert_eq!(
            path(8),
            Some((RareCasePath::Parallel, "tritri_pipeline_w8".into()))
        );
        assert_eq!(
            path(16),
            Some((RareCasePath::Shared, "tritri_pipeline_shared_w16".into()))
        );
        assert_eq!(path(24), None);
    }
}
