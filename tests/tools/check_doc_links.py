#!/usr/bin/env python3
"""The README and the documents stand alone: every relative link in README.md,
docs/*.md, tests/README.md and bench/README.md names a file or folder inside the
repository that exists (anchors aside), and no text points outside it ("../shared").
Usage: check_doc_links.py REPO_ROOT. Exit 1 with each bad link and its line."""

import os
import re
import sys

LINK = re.compile(r"\]\(([^)\s]+)\)")


def main(root):
    root = os.path.realpath(root)
    files = [os.path.join(root, "README.md"), os.path.join(root, "tests", "README.md"),
             os.path.join(root, "bench", "README.md")]
    docs = os.path.join(root, "docs")
    files += [os.path.join(docs, f) for f in sorted(os.listdir(docs)) if f.endswith(".md")]
    problems, links = [], 0
    for path in files:
        if not os.path.exists(path):
            continue
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                where = "%s:%d" % (os.path.relpath(path, root), number)
                if "../shared" in line:
                    problems.append("%s: points outside the repository (../shared)" % where)
                for target in LINK.findall(line):
                    if re.match(r"^[a-z]+:", target) or target.startswith("#"):
                        continue        # a web address or an anchor of this page
                    links += 1
                    file_part = target.split("#", 1)[0]
                    resolved = os.path.realpath(os.path.join(os.path.dirname(path), file_part))
                    if not (resolved + os.sep).startswith(root + os.sep):
                        problems.append("%s: %s points outside the repository" % (where, target))
                    elif not os.path.exists(resolved):
                        problems.append("%s: %s does not exist" % (where, target))
    print("\n".join(problems) or "%d links in %d documents, all inside the repository" % (
        links, len(files)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
