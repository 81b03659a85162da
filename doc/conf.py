# Sphinx configuration of the USER-TLSPH documentation (the style pages are
# written as LAMMPS's own: reStructuredText, :doc: links between pages).
#   python3 -m sphinx -b html -W doc build/doc-html      (the test doc.sphinx_html)
# Debian 12: python3-sphinx. Pages of the LAMMPS manual referenced with
# :doc:`fix nve <fix_nve>` are not part of this tree: they become links to
# the same page of the online LAMMPS manual (below), as in LAMMPS's own
# documentation, where those pages sit next to ours.

project = "USER-TLSPH"
author = "the tlsph developers"
copyright = "2026, the tlsph developers"
master_doc = "index"
source_suffix = {".rst": "restructuredtext"}
# Markdown reports (bench.md, pareto.md, roofline.md) are read on GitHub
# or as plain text, not built
exclude_patterns = ["*.md", "_build"]
html_theme = "alabaster"
html_static_path = []
highlight_language = "none"

LAMMPS_MANUAL = "https://docs.lammps.org/"


def _lammps_doc(app, env, node, contnode):
    """a :doc: target that is not one of our pages: the LAMMPS manual page"""
    from docutils import nodes

    if node.get("reftype") != "doc":
        return None
    target = node.get("reftarget", "")
    if not target or target in env.found_docs:
        return None
    # a page name of ours that does not exist (a typo) stays a warning
    if "tlsph" in target.lower() or target.startswith(("Howto_load", "validation")):
        return None
    ref = nodes.reference("", "", internal=False, refuri=f"{LAMMPS_MANUAL}{target}.html")
    ref.append(contnode)
    return ref


def _lammps_lexer():
    """input-script highlighting (LAMMPS's manual registers a lexer of that
    name too): the command word, comments, variables, numbers"""
    from pygments.lexer import RegexLexer, bygroups
    from pygments.token import Comment, Keyword, Name, Number, String, Text

    class LammpsLexer(RegexLexer):
        name = "LAMMPS"
        aliases = ["lammps"]
        tokens = {
            "root": [
                (r"#.*?$", Comment),
                (r"^(\s*)([a-z_][\w/]*)", bygroups(Text, Keyword)),
                (r"\$\{\w+\}|\$\w|v_\w+|c_\w+(\[\d+\])?|f_\w+(\[\d+\])?", Name.Variable),
                (r'"[^"]*"|\'[^\']*\'', String),
                (r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?\b", Number),
                (r"\s+", Text),
                (r"\S", Text),
            ]
        }

    return LammpsLexer


def setup(app):
    app.add_lexer("LAMMPS", _lammps_lexer())
    app.connect("missing-reference", _lammps_doc)
    return {"parallel_read_safe": True}
