"""Writes the long-input run's seeds (scripts/fuzz.sh SECONDS long) into the directory given:
flat chains of every kind the grammar allows, around the parser's height limit and far past
it, so the fuzzer mutates inputs that reach the stack-depth checks. Generated, not committed,
because they are large and easy to make."""
import pathlib
import sys

out = pathlib.Path(sys.argv[1])
out.mkdir(parents=True, exist_ok=True)
pieces = {
    "sum": ("x = 1", " + 1", ""),
    "power": ("x = 1", " ** 1", ""),
    "and": ("x = True", " and True", ""),
    "negation": ("x = ", "-", "1"),
    "not": ("x = ", "not ", "True"),
    "calls": ("def f():\n    return f\nx = f", "()", ""),
    "methods": ("x = Vector3D(1, 0, 0)", ".normalized()", ""),
    "subscripts": ("x = [0]", "[0]", ""),
    "conditional": ("x = 1", " if True else 1", ""),
    "brackets": ("x = ", "(", "1"),
    "relative": ("x = Vector3D(1, 0, 0)", " relative to Vector3D(0, 0, 0)", ""),
}
for name, (head, piece, tail) in pieces.items():
    for terms in (390, 410, 20_000):
        text = head + piece * terms + tail
        if name == "brackets":
            text += ")" * terms
        (out / f"long_{name}_{terms}.prs").write_text(text + "\n")
(out / "long_nested_tuples.prs").write_text("x = ()\nfor i in range(1500):\n    x = (x,)\n")
