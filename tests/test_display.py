"""HTML / LaTeX rendering of claim results (symbt.report.html)."""
from __future__ import annotations

import html.parser

from symbt.claims.base import Claim, ClaimResult, Outcome
from symbt.report.html import STATUS_COLOURS, latex_text, result_html, result_latex, scene_html


def _claim(**kw):
    d = dict(id="demo.n2", equation="eq:lax", statement="det L = 1 <always> & tr L = A + D",
             check=lambda: None, scene="toda", N=2)
    d.update(kw)
    return Claim(**d)


def _erratum():
    c = _claim(id="n3-ham", equation="n3-hamiltonians", statement="H_2 = p1p2 + p2p2 + ...", N=3,
               where="Numerics subsection")
    o = Outcome("erratum", "printed: exact | corrected: exact", residual=0.25, digits=None,
                printed="H_2 = p1*p2 + p2*p2 + p3*p1 - ...", corrected="H_2 = p1*p2 + p2*p3 + p3*p1 - ...",
                counterexample={"p1": "0.5", "q<1>": "1.25"}, seconds=0.1)
    return ClaimResult(c, o)


class _Checker(html.parser.HTMLParser):
    """Collects text and fails on unbalanced tags (a cheap well-formedness check)."""

    VOID = {"br", "hr", "img", "meta", "input"}

    def __init__(self):
        super().__init__()
        self.stack, self.text = [], []

    def handle_starttag(self, tag, attrs):
        if tag not in self.VOID:
            self.stack.append(tag)

    def handle_endtag(self, tag):
        assert self.stack and self.stack[-1] == tag, (tag, self.stack)
        self.stack.pop()

    def handle_data(self, data):
        self.text.append(data)


def _parse(h):
    p = _Checker()
    p.feed(h)
    p.close()
    assert p.stack == []
    return "".join(p.text)


def test_verified_card_shows_id_label_status_and_escapes():
    r = ClaimResult(_claim(), Outcome("verified", "exact: together/cancel", residual=0.0, seconds=0.01))
    h = r._repr_html_()
    assert h == result_html(r)
    assert "demo.n2" in h and "eq:lax" in h and "verified" in h
    assert STATUS_COLOURS["verified"] in h
    assert "&lt;always&gt; &amp; tr L" in h and "<always>" not in h
    text = _parse(h)
    assert "det L = 1 <always> & tr L = A + D" in text and "0 (exact)" in text


def test_erratum_card_shows_printed_counterexample_and_correction():
    r = _erratum()
    h = result_html(r)
    text = _parse(h)
    assert "erratum" in text and STATUS_COLOURS["erratum"] in h
    assert "printed" in text and "p2*p2" in text
    assert "corrected" in text and "p2*p3" in text
    assert "counterexample" in text and "q<1> = 1.25" in text and "q&lt;1&gt;" in h
    assert "Numerics subsection" in text


def test_failed_detail_is_preformatted_and_escaped():
    o = Outcome("failed", "exception", detail="ValueError: <bad>\nTraceback ...")
    h = result_html(ClaimResult(_claim(), o))
    assert "<pre" in h and "&lt;bad&gt;" in h and STATUS_COLOURS["failed"] in h
    _parse(h)


def test_latex_escapes_specials():
    r = _erratum()
    tex = r._repr_latex_()
    assert tex == result_latex(r)
    assert tex.startswith("$") and tex.endswith("$")
    assert r"n3-ham" in tex and r"n3-hamiltonians" in tex and "erratum" in tex
    assert r"H\_2" in tex and "corrected" in tex
    assert latex_text("a_b & {c}%$#^~\\") == (r"a\_b \& \{c\}\%\$\#\textasciicircum{}"
                                                r"\textasciitilde{}\textbackslash{}")


def test_scene_table():
    ok = ClaimResult(_claim(), Outcome("verified", "exact: together/cancel", residual=0.0))
    sk = ClaimResult(_claim(id="x<y>"), Outcome("skipped", "none", detail="no flint"))
    h = scene_html([ok, _erratum(), sk], title="toda & friends")
    text = _parse(h)
    assert h.count("<tr") == 4
    assert "3 claims: 1 verified, 1 erratum, 0 failed, 1 skipped" in text
    assert "x&lt;y&gt;" in h and "toda &amp; friends" in h
    assert "p2*p3" in text  # the erratum's correction is shown in the table


def test_real_claim_renders():
    from symbt.claims import REGISTRY, load_all

    load_all()
    r = REGISTRY["tn2"].result()
    h = r._repr_html_()
    assert "tn2" in h and r.status in h
    _parse(h)
