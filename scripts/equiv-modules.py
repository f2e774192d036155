"""Two emissions of one design, module by module, when module names differ
between them (a change to the emitter's naming): each module of OLD is
renamed to the NEW module that stands for the same instance (the first
instance path in its header), then Yosys proves every module equivalent
with the other modules as black boxes (equiv_make, equiv_simple,
equiv_induct), as the test emission_passes_are_formally_equivalent does
for one emission's rewrites. A memory is mapped to registers, so use a
small depth for a system (`--depth 16`).

    python3 scripts/equiv-modules.py OLD_DIR NEW_DIR TOP

Prints one line per module that is not proven and a count; exit status 1
if any is not.
"""
import re, sys, subprocess, pathlib, tempfile, shutil
if len(sys.argv) != 4:
    sys.exit(__doc__)
old, new, top = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3]

def first_instance(text):
    m = re.search(r"// Purpose:(.*?)\n//\n", text, re.S)
    body = " ".join(l.strip("/ ").strip() for l in m.group(1).split("\n"))
    m = re.search(r"Instances?(?: \(\d+\))?(?:, for example)?:\s*([^,]+?)[,.](?:\s|$)", body)
    return m.group(1).strip() if m else None

def modules(d):
    out = {}
    for f in d.glob("*.v"):
        t = f.read_text()
        name = re.search(r"^module (\w+)", t, re.M)
        if not name: continue
        out[name.group(1)] = (first_instance(t), t)
    return out

mo, mn = modules(old), modules(new)
by_instance = {inst: name for name, (inst, _) in mn.items() if inst}
mapping = {top: top}
for name, (inst, _) in mo.items():
    if name == top: continue
    if inst is None or inst not in by_instance:
        print("unmatched old module", name, inst); continue
    mapping[name] = by_instance[inst]
w = pathlib.Path(tempfile.mkdtemp())
(w / "gold").mkdir(); (w / "gate").mkdir()
pattern = re.compile(r"\b(" + "|".join(sorted(map(re.escape, mapping), key=len, reverse=True)) + r")\b")
for name, (_, t) in mo.items():
    if name not in mapping: continue
    (w / "gold" / f"{mapping[name]}.v").write_text(pattern.sub(lambda m: mapping[m.group(1)], t))
for f in new.glob("*.v"):
    shutil.copy(f, w / "gate" / f.name)
# Files of the new emission that hold no matched module (device models).
matched = set(mapping.values())
extra = " ".join(f"gate/{f.name}" for f in new.glob("*.v") if f.stem not in matched)
failed = 0; proven = 0
for name in sorted(matched):
    others = " ".join(f"gate/{m}.v" for m in sorted(matched) if m != name)
    script = (f"read_verilog -lib {others} {extra}\nread_verilog gold/{name}.v\nproc\nmemory\nrename {name} gold\n"
              f"read_verilog gate/{name}.v\nproc\nmemory\nrename {name} gate\nequiv_make gold gate equiv\n"
              "hierarchy -top equiv\nequiv_simple\nequiv_induct\nequiv_status -assert\n")
    (w / "e.ys").write_text(script)
    r = subprocess.run(["yosys", "-q", "e.ys"], cwd=w, capture_output=True, text=True)
    if r.returncode != 0:
        failed += 1
        print("NOT PROVEN", name, r.stderr[-400:] or r.stdout[-400:])
    else:
        proven += 1
shutil.rmtree(w)
print(f"{proven} modules proven equivalent, {failed} not; {len(mo)} old modules, {len(mn)} new")
sys.exit(1 if failed or len(mapping) != len(mo) else 0)
