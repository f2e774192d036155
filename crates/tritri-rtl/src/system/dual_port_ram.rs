//! A simple dual-port memory: one write port and one registered read port
//! on one clock, the shape FPGA block RAMs implement directly.
//!
//! * Write: when `write_enable` is high at a rising edge, `write_data` is
//!   stored at `write_address`.
//! * Read: when `read_enable` is high at a rising edge, `read_data` takes
//!   the word at `read_address` as it was before that edge (read-first);
//!   with `read_enable` low it holds, which is how a stalled reader keeps
//!   its data.
//!
//! With an output register ([`SimpleDualPortRam::with_output_register`])
//! a read takes two clocks: the word goes through a second register, also
//! enabled by `read_enable`, so both stages hold together. Block RAMs have
//! that register too (ECP5's DP16KD: `REGMODE = "OUTREG"`), and it is what
//! makes them fast: without it a DP16KD takes 5.8 ns from clock to data.
//! Inferred, the second register lands in fabric; `--dsp ecp5` instantiates
//! the DP16KD with it ([`crate::emit::block_ram_mapping`]).
//!
//! The depth (`words`) is a run-time generator parameter; the address is
//! `A` bits wide. The simulation model is a `Vec`, so a large memory costs
//! nothing per cycle.

use rust_hdl::prelude::*;

/// How the body of a RAM with an output register starts, followed by
/// `<words> words of <bits> bit(s)` (what [`crate::emit::block_ram_mapping`]
/// reads).
pub const OUTPUT_REGISTER_SHAPE: &str = "// Simple dual-port RAM with an output register: ";

#[derive(LogicBlock)]
pub struct SimpleDualPortRam<T: Synth, const A: usize> {
    pub clock: Signal<In, Clock>,
    pub write_enable: Signal<In, Bit>,
    pub write_address: Signal<In, Bits<A>>,
    pub write_data: Signal<In, T>,
    pub read_enable: Signal<In, Bit>,
    pub read_address: Signal<In, Bits<A>>,
    pub read_data: Signal<Out, T>,
    _memory: Vec<T>,
    /// Ask synthesis for block RAM even where the memory is small enough
    /// for distributed RAM (`ram_style = "block"`, read by Yosys and
    /// Vivado).
    _block_ram: bool,
    /// A second read register (`with_output_register`), and its word.
    _output_register: bool,
    _stage: T,
}

impl<T: Synth, const A: usize> crate::unit::Unit for SimpleDualPortRam<T, A> {
    fn settings(&self) -> Vec<(&'static str, String)> {
        let mut settings = vec![("depth", self.words().to_string())];
        if self._output_register {
            settings.push(("read_stages", "2".to_string()));
        }
        settings
    }
}

impl<T: Synth, const A: usize> SimpleDualPortRam<T, A> {
    pub fn new(words: usize) -> Self {
        assert!(
            words >= 1 && words <= 1 << A,
            "a RAM of {words} words needs more than {A} address bits"
        );
        SimpleDualPortRam {
            clock: Default::default(),
            write_enable: Default::default(),
            write_address: Default::default(),
            write_data: Default::default(),
            read_enable: Default::default(),
            read_address: Default::default(),
            read_data: Default::default(),
            _memory: vec![T::default(); words],
            _block_ram: false,
            _output_register: false,
            _stage: T::default(),
        }
    }

    /// [`Self::new`] with an output register: a read takes two clocks.
    pub fn with_output_register(words: usize) -> Self {
        SimpleDualPortRam {
            _output_register: true,
            ..Self::new(words)
        }
    }

    /// The same memory in block RAM whatever its size: a block RAM's
    /// address pins are a few loads, where a small memory in distributed
    /// RAM spreads its read address over dozens of LUTs.
    pub fn in_block_ram(self) -> Self {
        SimpleDualPortRam {
            _block_ram: true,
            ..self
        }
    }

    pub fn words(&self) -> usize {
        self._memory.len()
    }
}

impl<T: Synth, const A: usize> Logic for SimpleDualPortRam<T, A> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            if self.read_enable.val() {
                let address = self.read_address.val().index();
                let word = self._memory.get(address).copied().unwrap_or_default();
                if self._output_register {
                    self.read_data.next = self._stage;
                    self._stage = word;
                } else {
                    self.read_data.next = word;
                }
            }
            if self.write_enable.val() {
                let address = self.write_address.val().index();
                if let Some(word) = self._memory.get_mut(address) {
                    *word = self.write_data.val();
                }
            }
        }
    }

    fn connect(&mut self) {
        self.read_data.connect();
    }

    fn hdl(&self) -> Verilog {
        let words = self._memory.len();
        let data_range = if T::BITS == 1 {
            String::new()
        } else {
            format!("[{}:0] ", T::BITS - 1)
        };
        // The memory is indexed with just the address bits it needs.
        let index_bits = (usize::BITS - (words.max(2) - 1).leading_zeros()) as usize;
        let (write_index, read_index, unused) = if index_bits < A {
            (
                format!("write_address[{}:0]", index_bits - 1),
                format!("read_address[{}:0]", index_bits - 1),
                format!(
                    "\n// Address bits above the depth are always zero.\n\
                     // verilator lint_off UNUSEDSIGNAL\n\
                     wire unused_address_bits = ^{{write_address[{hi}:{lo}], read_address[{hi}:{lo}]}};\n\
                     // verilator lint_on UNUSEDSIGNAL\n",
                    hi = A - 1,
                    lo = index_bits
                ),
            )
        } else {
            (
                "write_address".to_string(),
                "read_address".to_string(),
                String::new(),
            )
        };
        let style = if self._block_ram {
            "(* ram_style = \"block\" *) "
        } else {
            ""
        };
        let bits = T::BITS;
        let last = words - 1;
        // With an output register, it starts at zero, as the model's does.
        let (heading, stage, read) = if self._output_register {
            (
                format!(
                    "{OUTPUT_REGISTER_SHAPE}{words} words of {bits} bit(s), read-first,\n\
                     // registered read and an output register, both with enable (block RAM\n\
                     // inference; the output register in fabric)."
                ),
                format!("reg {data_range}read_stage;\ninitial read_data = {bits}'d0;\n"),
                format!(
                    "        read_stage <= memory[{read_index}];\n        read_data <= read_stage;\n"
                ),
            )
        } else {
            (
                format!(
                    "// Simple dual-port RAM: {words} words of {bits} bit(s), read-first,\n\
                     // registered read with enable (block RAM inference)."
                ),
                String::new(),
                format!("        read_data <= memory[{read_index}];\n"),
            )
        };
        Verilog::Custom(format!(
            "\
{heading}
{style}reg {data_range}memory [0:{last}];
{stage}{unused}
always @(posedge clock) begin
    if (write_enable) begin
        memory[{write_index}] <= write_data;
    end
    if (read_enable) begin
{read}    end
end
"
        ))
    }
}
