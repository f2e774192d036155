//! nextpnr's device utilisation, read from its log: what a design needs of
//! each kind of cell against what the device has, so that a design that
//! does not fit gets one error naming each resource that is over, with
//! its count and the device's, instead of the tool's traceback.

/// One line of nextpnr's "Device utilisation" table.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Utilisation {
    /// nextpnr's cell type (`TRELLIS_COMB`, `MULT18X18D`, `DP16KD`, ...).
    pub resource: String,
    pub used: u64,
    pub available: u64,
}

impl Utilisation {
    /// Whether the design needs more of it than the device has.
    pub fn is_over(&self) -> bool {
        self.used > self.available
    }
}

impl std::fmt::Display for Utilisation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {} of {}", self.resource, self.used, self.available)?;
        if self.available > 0 {
            write!(f, " ({:.1} x)", self.used as f64 / self.available as f64)?;
        }
        Ok(())
    }
}

/// The last "Device utilisation" table of a nextpnr log (it prints one
/// after packing and one after placement), or nothing if there is none.
/// Its lines read `Info: \t          MULT18X18D:  1754/  156  1124%`.
pub fn read_utilisation(log: &str) -> Vec<Utilisation> {
    let mut table = Vec::new();
    let mut inside = false;
    for line in log.lines() {
        let text = line.strip_prefix("Info:").unwrap_or(line).trim();
        if text.starts_with("Device utilisation") {
            table.clear();
            inside = true;
            continue;
        }
        if !inside {
            continue;
        }
        match utilisation_line(text) {
            Some(row) => table.push(row),
            None => inside = false,
        }
    }
    table
}

/// `MULT18X18D:  1754/  156  1124%`.
fn utilisation_line(text: &str) -> Option<Utilisation> {
    let (resource, counts) = text.split_once(':')?;
    let (used, rest) = counts.split_once('/')?;
    let available = rest.split_whitespace().next()?;
    Some(Utilisation {
        resource: resource.trim().to_string(),
        used: used.trim().parse().ok()?,
        available: available.parse().ok()?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A table in the format of this flow's nextpnr-ecp5 log (as the
    /// owner filter's route_ecp5.log has it), with the counts the issue
    /// reports for the broad-phase top: eleven times the multipliers of an
    /// ECP5-85.
    const LOG: &str = "Info: Packing IOs..\n\
Info: Device utilisation:\n\
Info: \t          TRELLIS_IO:     0/  365     0%\n\
Info: \t        TRELLIS_COMB: 286000/83640   341%\n\
Info: \t          MULT18X18D:  1754/  156  1124%\n\
Info: \t              DP16KD:   205/  208    98%\n\
Info: \n\
Info: Placed 0 cells based on constraints.\n\
ERROR: Unable to place cell 'x', no BELs remaining to implement cell type 'MULT18X18D'\n";

    #[test]
    fn the_resources_over_the_device_are_read_from_the_log() {
        let table = read_utilisation(LOG);
        assert_eq!(table.len(), 4);
        let over: Vec<String> = table
            .iter()
            .filter(|u| u.is_over())
            .map(|u| u.to_string())
            .collect();
        assert_eq!(
            over,
            [
                "TRELLIS_COMB 286000 of 83640 (3.4 x)",
                "MULT18X18D 1754 of 156 (11.2 x)"
            ]
        );
    }

    #[test]
    fn a_log_without_the_table_reads_as_none() {
        assert!(read_utilisation("Info: Packing IOs..\nERROR: no such file\n").is_empty());
    }
}
