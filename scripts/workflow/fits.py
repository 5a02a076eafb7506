"""Least-squares fits of a study's trends (docs/studies.md, "Plots"), numpy only.

  parabola              y = a x^2 + b x + c with a <= 0 (concave): the unconstrained fit,
                        or the straight line (a = 0) when that would be convex
  exponential           y = a exp(b x) + c, or y = a exp(b x) without the offset
  decaying_exponential  y = a exp(-b x) + c with b > 0

The exponentials are linear in a and c for a given b: b is found by a search over a
logarithmic grid of rates scaled by the x range, refined by golden-section search.
Each fit returns its coefficients, R^2 = 1 - SS_res / SS_tot and a function to draw it.
"""
import math

import numpy as np


class Fit:
    def __init__(self, kind, coefficients, x, y, predict, note=""):
        self.kind, self.coefficients, self.predict, self.note = kind, coefficients, predict, note
        residual = y - predict(x)
        total = np.sum((y - np.mean(y)) ** 2)
        self.r2 = 1.0 - np.sum(residual**2) / total if total > 0 else float("nan")
        self.points = len(x)

    def formula(self):
        a, b, c = (self.coefficients + [0.0, 0.0, 0.0])[:3]
        if self.kind == "parabola":
            return f"{a:.4g} x² + {b:.4g} x + {c:.4g}"
        if self.kind == "decaying_exponential":
            return f"{a:.4g} exp(-{b:.4g} x) + {c:.4g}"
        return f"{a:.4g} exp({b:.4g} x)" + (f" + {c:.4g}" if len(self.coefficients) == 3 else "")


def parabola(x, y):
    a, b, c = np.polyfit(x, y, 2)
    note = ""
    if a > 0:  # the best concave parabola is then the straight line
        b, c = np.polyfit(x, y, 1)
        a, note = 0.0, "concavity constraint active: a = 0"
    return Fit("parabola", [float(a), float(b), float(c)], x, y, lambda t: a * t**2 + b * t + c, note)


def _linear_part(x, y, rate, offset):
    """Best a (and c) for a given rate; returns (sse, coefficients)."""
    e = np.exp(rate * (x - x.min()))  # shifted for conditioning; a is rescaled below
    design = np.column_stack([e, np.ones_like(e)]) if offset else e[:, None]
    coef, *_ = np.linalg.lstsq(design, y, rcond=None)
    sse = float(np.sum((design @ coef - y) ** 2))
    a = coef[0] * math.exp(-rate * x.min())
    return sse, [float(a), float(rate)] + ([float(coef[1])] if offset else [])


def _search_rate(x, y, rates, offset):
    errors = [_linear_part(x, y, r, offset)[0] for r in rates]
    i = int(np.argmin(errors))
    lo, hi = rates[max(i - 1, 0)], rates[min(i + 1, len(rates) - 1)]
    phi = (math.sqrt(5) - 1) / 2
    for _ in range(80):  # golden section between the grid neighbours of the best rate
        m1, m2 = hi - phi * (hi - lo), lo + phi * (hi - lo)
        if _linear_part(x, y, m1, offset)[0] < _linear_part(x, y, m2, offset)[0]:
            hi = m2
        else:
            lo = m1
    return _linear_part(x, y, 0.5 * (lo + hi), offset)[1]


def exponential(x, y, offset=True):
    span = max(x.max() - x.min(), 1e-300)
    magnitudes = np.logspace(-3, 2, 200) / span
    rates = np.concatenate([-magnitudes[::-1], magnitudes])
    a, b, *c = _search_rate(x, y, rates, offset)
    c0 = c[0] if c else 0.0
    return Fit("exponential", [a, b] + c, x, y, lambda t: a * np.exp(b * t) + c0)


def decaying_exponential(x, y):
    span = max(x.max() - x.min(), 1e-300)
    rates = -np.logspace(-3, 2, 200)[::-1] / span
    a, b, c = _search_rate(x, y, rates, True)
    return Fit("decaying_exponential", [a, -b, c], x, y, lambda t: a * np.exp(b * t) + c)


def fit(kind, x, y, offset=True):
    """None when there are too few points for the kind of fit."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    keep = np.isfinite(x) & np.isfinite(y)
    x, y = x[keep], y[keep]
    needed = 2 if (kind == "exponential" and not offset) else 3
    if len(x) < needed:
        return None
    if kind == "parabola":
        return parabola(x, y)
    if kind == "exponential":
        return exponential(x, y, offset)
    return decaying_exponential(x, y)
