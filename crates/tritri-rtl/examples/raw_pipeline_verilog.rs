//! Prints rust-hdl's raw Verilog of the triangle pipeline:
//! `cargo run --release -p tritri-rtl --example raw_pipeline_verilog -- 24 > top.v`
fn main() {
    let width: usize = std::env::args()
        .nth(1)
        .map(|w| w.parse().expect("width"))
        .unwrap_or(24);
    print!(
        "{}",
        tritri_rtl::raw_design(width)
            .expect("supported width")
            .verilog
    );
}
