"""The documentation's mathematics reaches MathJax: no LaTeX is left as text by the Markdown parser.

A line of a paragraph that starts with ``+ `` or ``- `` is a list item to
Markdown, which cuts an inline formula that runs over it in two and prints its
LaTeX raw; a Python string without ``r`` turns ``\\frac`` into a form feed and
``\\tfrac`` into a tab.  The pages are parsed with MyST's parser and the
documentation's extensions (``docs/conf.py``): every backslash command must end
up inside a math token.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parents[2] / "docs"
PAGES = sorted(DOCS.rglob("*.md"))
#: A LaTeX command or a dollar sign: in the text of a parsed page, a formula the parser did not see.
RAW_LATEX = re.compile(r"\\[A-Za-z]{2,}|\$")


def test_the_pages_have_no_control_characters():
    for page in PAGES:
        bad = [(n, line) for n, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1)
               if re.search(r"[\x00-\x08\x0b-\x1f]", line)]
        assert bad == [], page


def raw_latex(text: str) -> list[str]:
    """Text pieces of the parsed page that hold LaTeX (outside math, code and HTML)."""
    pytest.importorskip("myst_parser")
    from markdown_it.renderer import RendererHTML
    from myst_parser.config.main import MdParserConfig
    from myst_parser.parsers.mdit import create_md_parser

    md = create_md_parser(MdParserConfig(enable_extensions={"dollarmath", "amsmath"}, dmath_double_inline=True),
                          RendererHTML)
    return [child.content for token in md.parse(text) if token.type == "inline"
            for child in token.children if child.type == "text" and RAW_LATEX.search(child.content)]


def test_a_formula_cut_by_a_line_starting_with_plus_is_detected():
    broken = "The potential,\n$V = a\n+ \\tfrac12 k x^2$,\nhas the Hessian\n"
    assert raw_latex(broken) != []
    assert raw_latex(broken.replace("a\n+ ", "a +\n")) == []


@pytest.mark.parametrize("page", PAGES, ids=[p.relative_to(DOCS).as_posix() for p in PAGES])
def test_no_latex_is_left_as_text(page):
    assert raw_latex(page.read_text(encoding="utf-8")) == []
