//! The triangle pipeline's ports, declared once: [`pipeline_ports!`](crate::pipeline_ports) writes
//! them into the real pipeline ([`super::triangle_pipeline`]) and into the
//! stub the system tests use ([`crate::system::stub_pipeline`]), and
//! [`port_descriptions`] says what each means, for the emitted README, the
//! top's header and the port check of the emitter (a port without a
//! description, or a description without a port, is an emission error).
//! The collision system drives them by these names.

/// Declares a pipeline struct with the pipeline's ports first, then the
/// fields given:
///
/// ```ignore
/// pipeline_ports! {
///     #[derive(LogicBlock, Default)]
///     pub struct TrianglePipeline<const W: usize, const D: usize, ...> {
///         front_end: TriangleFrontEnd<W, D, C>,
///     }
/// }
/// ```
#[macro_export]
macro_rules! pipeline_ports {
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident<const W: usize $(, const $param:ident: usize)* $(,)?> {
            $($fields:tt)*
        }
    ) => {
        $(#[$meta])*
        $vis struct $name<const W: usize $(, const $param: usize)*> {
            pub clock: Signal<In, Clock>,
            pub reset: Signal<In, Bit>,
            pub advance: Signal<In, Bit>,
            pub in_valid: Signal<In, Bit>,
            pub in_bset: Signal<In, Bit>,
            pub in_id: Signal<In, Bits<{ $crate::pipeline::ID_BITS }>>,
            pub in_x0: Signal<In, Bits<W>>,
            pub in_y0: Signal<In, Bits<W>>,
            pub in_z0: Signal<In, Bits<W>>,
            pub in_x1: Signal<In, Bits<W>>,
            pub in_y1: Signal<In, Bits<W>>,
            pub in_z1: Signal<In, Bits<W>>,
            pub in_x2: Signal<In, Bits<W>>,
            pub in_y2: Signal<In, Bits<W>>,
            pub in_z2: Signal<In, Bits<W>>,
            pub out_valid: Signal<Out, Bit>,
            pub out_hit: Signal<Out, Bit>,
            pub out_certain: Signal<Out, Bit>,
            pub out_base_id: Signal<Out, Bits<{ $crate::pipeline::ID_BITS }>>,
            pub out_stream_id: Signal<Out, Bits<{ $crate::pipeline::ID_BITS }>>,
            $($fields)*
        }
    };
}

/// Every port of [`pipeline_ports!`](crate::pipeline_ports) with its meaning, for a pipeline of
/// latency `latency`.
pub fn port_descriptions(latency: usize) -> Vec<(String, String)> {
    let mut ports: Vec<(String, String)> = [
        ("clock", "Clock; every register updates on the rising edge.".to_string()),
        ("reset", "Synchronous reset, active high: clears the valid bits (the datapath has no reset).".into()),
        ("advance", "Clock enable: while low, every register, the base polygon included, holds (back-pressure).".into()),
        ("in_valid", "A triangle is on the input bus this cycle.".into()),
        ("in_bset", "With `in_valid`: load this triangle as the base polygon T1 instead of testing it.".into()),
        ("in_id", "Id of the triangle, returned as `out_base_id` or `out_stream_id`.".into()),
        ("out_valid", format!("A verdict is on the outputs: the streamed triangle entered {latency} clocks earlier.")),
        ("out_hit", "1 when the base and the streamed triangle intersect (touching counts).".into()),
        (
            "out_certain",
            "1 when `out_hit` is provably the verdict on the coordinates before quantization: no sign it rests on \
             changes if every coordinate moves by half a grid step (docs/certificates.md). Coplanar and degenerate \
             pairs are never certain; the host decides a pair with `out_certain = 0` again on its own coordinates."
                .into(),
        ),
        ("out_base_id", "Id of the base triangle of this verdict.".into()),
        ("out_stream_id", "Id of the streamed triangle of this verdict.".into()),
    ]
    .into_iter()
    .map(|(n, d)| (n.to_string(), d))
    .collect();
    for vertex in 0..3 {
        for axis in ["x", "y", "z"] {
            ports.push((
                format!("in_{axis}{vertex}"),
                format!("Coordinate {axis} of vertex {vertex}, W-bit two's complement."),
            ));
        }
    }
    ports
}
