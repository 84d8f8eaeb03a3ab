"""The generated part of a Markdown document: the block between `<!-- NAME:begin -->` and
`<!-- NAME:end -->`, which scripts/update-accuracy.sh (bench) and scripts/update-performance.sh
(levers) rewrite while leaving the prose around it alone."""
import re
import sys


def replace_block(doc_path, name, block):
    """Puts `block` between the NAME markers of doc_path; exits naming both markers when the
    document lacks them."""
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    doc = open(doc_path).read()
    pattern = re.compile("(" + re.escape(begin) + r"\n).*?(" + re.escape(end) + ")", re.S)
    if not pattern.search(doc):
        sys.exit(f"{doc_path}: the markers {begin} and {end} are missing")
    doc = pattern.sub(lambda m: m.group(1) + block + "\n" + m.group(2), doc)
    open(doc_path, "w").write(doc)
