"""Write validation/derived_vs_published.md: derived vs published Table 2, entry by entry.

Run: ``python validation/make_parameter_table.py [--turnout FILE] [--out FILE]``.
"""

import argparse
from pathlib import Path

from exudyn_turnout.corunning.comparison import compare_with_table2, comparison_markdown
from exudyn_turnout.inputs.turnout import load_turnout


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--turnout", help="turnout file (default: the packaged UIC60-760-1:15)")
    parser.add_argument("--out", default=str(Path(__file__).with_name("derived_vs_published.md")))
    args = parser.parse_args(argv)
    turnout = load_turnout(args.turnout)
    rows = compare_with_table2(turnout)
    Path(args.out).write_text(comparison_markdown(rows, turnout), encoding="utf-8")
    print(f"wrote {args.out}: {sum(r.reproduced for r in rows)} of {len(rows)} entries reproduced")


if __name__ == "__main__":
    main()
