//! The designs `tritri gen` writes, as one table: the option that picks
//! each and the design options it takes.
//! Everything else `gen` decides about a design (its top's name, its
//! directory, how it is emitted and which widths it is built for) is a
//! `match` on [`Design`] in `gen.rs`, so that adding a design is adding a
//! row here and an arm there, and an option a design does not take is
//! refused by name ([`Design::refuse`]) instead of being ignored.

/// One design `tritri gen` can write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Design {
    /// The triangle pipeline (no design option given).
    Pipeline,
    /// The thesis's system: two-bank memories, address generator,
    /// pipelines, result FIFO.
    System,
    /// The broad phase's triangle classifier step.
    Classifier,
    /// The setup that feeds the classifier.
    Setup,
    /// The broad phase's binning unit.
    BinningUnit,
    /// The broad-phase top: binning unit, collision system, owner filter.
    BroadPhase,
    /// The broad phase's owner filter, slot-table form.
    OwnerFilter,
    /// The broad-phase tops' owner filter, chain form.
    OwnerChainFilter,
    /// The octree engine's plane classification.
    PlaneTraversal,
    /// The octree engine's set operations on voxel models.
    SetOperation,
    /// The octree engine's clipping against a box.
    OctantClipper,
    /// The octree engine's voxel memory side.
    VoxelFill,
    /// The octree engine's surface voxelization.
    TriangleVoxelizer,
    /// The octree engine's voxel to octree conversion.
    OctreeBuilder,
    /// The Bezier system's patch tessellation.
    PatchTessellator,
    /// The Bezier system's cone-of-normals test.
    ConeUnit,
    /// The pipeline's rare cases on one shared path.
    SharedRareCases,
    /// The AXI4 port's copy unit (burst reader into burst writer).
    AxiCopy,
    /// The broad phase's pass of a cell with its lists in external memory.
    ListPass,
    /// The broad phase's binning over such passes, every list in external
    /// memory.
    DramBinning,
    /// The broad-phase accelerator with its scene in external memory:
    /// that binning, the leaf reader, the collision system and the owner
    /// filter on one AXI4 port.
    DramBroadPhase,
}

/// An option that shapes a design; each design takes the ones its row
/// lists. (The flow's options, `--out`, `--synth`, `--seed` and the like,
/// apply to every design.)
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DesignOption {
    Width,
    Dsp,
    RareCases,
    Pipelines,
    Depth,
    Triangles,
    ListWords,
    Leaves,
    Slots,
    Steps,
    Assemble,
    DataBits,
}

impl DesignOption {
    /// The option as the command line spells it.
    pub fn flag(self) -> &'static str {
        match self {
            DesignOption::Width => "--width",
            DesignOption::Dsp => "--dsp",
            DesignOption::RareCases => "--rare-cases",
            DesignOption::Pipelines => "--pipelines",
            DesignOption::Depth => "--depth",
            DesignOption::Triangles => "--triangles",
            DesignOption::ListWords => "--list-words",
            DesignOption::Leaves => "--leaves",
            DesignOption::Slots => "--slots",
            DesignOption::Steps => "--steps",
            DesignOption::Assemble => "--assemble",
            DesignOption::DataBits => "--data-bits",
        }
    }
}

/// A row of the table.
pub struct Row {
    pub design: Design,
    /// The option that picks the design (none for the pipeline).
    pub flag: Option<&'static str>,
    /// The design options it takes. What `--width` means differs (the
    /// coordinates', the octree grid's, a unit's own list) and is checked
    /// per design in `gen.rs` (`check_width`).
    pub takes: &'static [DesignOption],
}

use DesignOption::*;

/// Every design, once. `--dsp` is taken by the designs with multipliers
/// (the MULT18X18D mapping applies to them).
pub const DESIGNS: [Row; 21] = [
    Row {
        design: Design::Pipeline,
        flag: None,
        takes: &[Width, Dsp, RareCases],
    },
    Row {
        design: Design::System,
        flag: Some("--system"),
        takes: &[Width, Dsp, RareCases, Pipelines, Depth],
    },
    Row {
        design: Design::Classifier,
        flag: Some("--classifier"),
        takes: &[Width],
    },
    Row {
        design: Design::Setup,
        flag: Some("--setup"),
        takes: &[Width],
    },
    Row {
        design: Design::BinningUnit,
        flag: Some("--binning-unit"),
        takes: &[Width, Pipelines, Depth, Triangles, ListWords, Leaves],
    },
    Row {
        design: Design::BroadPhase,
        flag: Some("--broad-phase"),
        takes: &[
            Width, Dsp, Pipelines, Depth, Triangles, ListWords, Leaves, Slots,
        ],
    },
    Row {
        design: Design::OwnerFilter,
        flag: Some("--owner-filter"),
        takes: &[Slots],
    },
    Row {
        design: Design::OwnerChainFilter,
        flag: Some("--owner-chain-filter"),
        takes: &[Triangles, Slots],
    },
    Row {
        design: Design::PlaneTraversal,
        flag: Some("--plane-traversal"),
        takes: &[],
    },
    Row {
        design: Design::SetOperation,
        flag: Some("--set-operation"),
        takes: &[],
    },
    Row {
        design: Design::OctantClipper,
        flag: Some("--octant-clipper"),
        takes: &[],
    },
    Row {
        design: Design::VoxelFill,
        flag: Some("--voxel-fill"),
        takes: &[],
    },
    Row {
        design: Design::TriangleVoxelizer,
        flag: Some("--triangle-voxelizer"),
        takes: &[],
    },
    Row {
        design: Design::OctreeBuilder,
        flag: Some("--octree-builder"),
        takes: &[],
    },
    Row {
        design: Design::PatchTessellator,
        flag: Some("--patch-tessellator"),
        takes: &[Width, Steps, Assemble],
    },
    Row {
        design: Design::ConeUnit,
        flag: Some("--cone-unit"),
        takes: &[Width],
    },
    Row {
        design: Design::SharedRareCases,
        flag: Some("--shared-rare-cases"),
        takes: &[Width, Dsp],
    },
    Row {
        design: Design::AxiCopy,
        flag: Some("--axi-copy"),
        takes: &[Width],
    },
    Row {
        design: Design::ListPass,
        flag: Some("--list-pass"),
        takes: &[Width, DataBits],
    },
    Row {
        design: Design::DramBinning,
        flag: Some("--dram-binning"),
        takes: &[Width, DataBits, Pipelines, Depth],
    },
    Row {
        design: Design::DramBroadPhase,
        flag: Some("--dram-broad-phase"),
        takes: &[
            Width, DataBits, Dsp, RareCases, Pipelines, Depth, Triangles, Slots,
        ],
    },
];

impl Design {
    /// The design's row.
    pub fn row(self) -> &'static Row {
        DESIGNS
            .iter()
            .find(|r| r.design == self)
            .expect("every design has a row")
    }

    /// Whether the design takes `option`.
    pub fn takes(self, option: DesignOption) -> bool {
        self.row().takes.contains(&option)
    }

    /// Whether the design has multipliers (`--dsp` applies).
    pub fn has_multipliers(self) -> bool {
        self.takes(Dsp)
    }

    /// The design as a message names it.
    pub fn named(self) -> String {
        match self.row().flag {
            Some(flag) => flag.to_string(),
            None => "the pipeline".to_string(),
        }
    }

    /// The first of `given` that the design does not take, as an error
    /// that names it and lists what the design does take.
    pub fn refuse(self, given: &[DesignOption]) -> Result<(), String> {
        let Some(option) = given.iter().find(|&&o| !self.takes(o)) else {
            return Ok(());
        };
        let takes: Vec<&str> = self.row().takes.iter().map(|o| o.flag()).collect();
        let takes = if takes.is_empty() {
            "it takes none of the design options".to_string()
        } else {
            format!("it takes {}", takes.join(", "))
        };
        let designs: Vec<String> = DESIGNS
            .iter()
            .filter(|r| r.design.takes(*option))
            .map(|r| r.design.named())
            .collect();
        Err(format!(
            "{} does not apply to {} ({takes}); it is for {}",
            option.flag(),
            self.named(),
            designs.join(", ")
        ))
    }
}

/// The one design among the options given (`picked`: each design's
/// option, whether given), or an error naming those that were given
/// together.
pub fn picked(given: &[(Design, bool)]) -> Result<Design, String> {
    let chosen: Vec<Design> = given.iter().filter(|g| g.1).map(|g| g.0).collect();
    match chosen.as_slice() {
        [] => Ok(Design::Pipeline),
        [one] => Ok(*one),
        several => Err(format!(
            "{}: gen writes one design at a time",
            several
                .iter()
                .map(|d| d.named())
                .collect::<Vec<_>>()
                .join(" and ")
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_design_has_one_row_and_its_own_flag() {
        for (i, row) in DESIGNS.iter().enumerate() {
            assert_eq!(row.design.row().flag, row.flag);
            assert!(
                DESIGNS[i + 1..]
                    .iter()
                    .all(|other| other.flag != row.flag && other.design != row.design),
                "{:?} twice",
                row.design
            );
        }
    }

    #[test]
    fn an_option_a_design_does_not_take_is_named() {
        assert_eq!(Design::VoxelFill.refuse(&[]), Ok(()));
        let refused = Design::VoxelFill.refuse(&[RareCases]).unwrap_err();
        assert_eq!(
            refused,
            "--rare-cases does not apply to --voxel-fill (it takes none of the design options); it is for the pipeline, --system, --dram-broad-phase"
        );
        let refused = Design::OwnerFilter.refuse(&[Slots, Width]).unwrap_err();
        // The list of designs that take --width grows with the table; the
        // message names the refused design, what it takes, and each design
        // with the option, in the table's order.
        let (head, users) = refused.split_once("; it is for ").unwrap();
        assert_eq!(
            head,
            "--width does not apply to --owner-filter (it takes --slots)"
        );
        let users: Vec<&str> = users.split(", ").collect();
        assert_eq!(users[..3], ["the pipeline", "--system", "--classifier"]);
        assert!(users.contains(&"--list-pass") && users.contains(&"--axi-copy"));
        assert!(!users.contains(&"--owner-filter") && !users.contains(&"--voxel-fill"));
        assert_eq!(Design::System.refuse(&[Width, Depth, Dsp]), Ok(()));
    }

    #[test]
    fn two_designs_at_once_are_refused_by_name() {
        assert_eq!(picked(&[(Design::System, false)]), Ok(Design::Pipeline));
        assert_eq!(
            picked(&[(Design::System, true), (Design::Setup, true)]).unwrap_err(),
            "--system and --setup: gen writes one design at a time"
        );
    }
}
