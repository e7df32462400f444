"""Suggestions for a mistyped name: the closest known one by edit distance.

Used for room ids (E102-E106), and by the CLI for ids given as flags (`--robot-room`).
"""

from __future__ import annotations

from collections.abc import Iterable

LOOKALIKES = frozenset({frozenset("O0"), frozenset("o0"), frozenset("I1"), frozenset("l1"), frozenset("Il")})
"""Characters a person easily types for each other: replacing one with the other costs half."""


def edit_distance(a: str, b: str) -> float:
    """Damerau-Levenshtein distance (an adjacent swap is one edit), where a change of case
    or of a look-alike (`O`/`0`, `l`/`1`) costs 0.5, so `CO` is closer to `C0` than `C1` is."""
    rows = [[0.0] * (len(b) + 1) for _ in range(len(a) + 1)]
    for i in range(len(a) + 1):
        rows[i][0] = float(i)
    for j in range(len(b) + 1):
        rows[0][j] = float(j)
    for i in range(1, len(a) + 1):
        for j in range(1, len(b) + 1):
            x, y = a[i - 1], b[j - 1]
            if x == y:
                cost = 0.0
            elif x.lower() == y.lower() or frozenset((x, y)) in LOOKALIKES:
                cost = 0.5
            else:
                cost = 1.0
            rows[i][j] = min(rows[i - 1][j] + 1, rows[i][j - 1] + 1, rows[i - 1][j - 1] + cost)
            if i > 1 and j > 1 and x == b[j - 2] and a[i - 2] == y:
                rows[i][j] = min(rows[i][j], rows[i - 2][j - 2] + 1)
    return rows[len(a)][len(b)]


def suggest(word: str, candidates: Iterable[str]) -> str | None:
    """The candidate closest to `word` by edit_distance, or None when none is close.

    Room ids are short (`C0`, `R12`), where difflib's ratio cutoff rejects every two-letter
    id; an edit count does not: one edit is allowed up to 4 characters, then one per 4 more
    (`C9` -> `C0`, `CO` -> `C0`, `KITCHN` -> `KITCHEN`). Among equally close candidates the
    one sharing the longest prefix wins (`C1` -> `C0`, not `R1`: the letter is the room's
    kind), then the one listed first.
    """
    allowed = max(1.0, len(word) / 4)
    best: tuple[float, int, str] | None = None
    for candidate in candidates:
        distance = edit_distance(word, candidate)
        if distance > allowed:
            continue
        key = (distance, -_common_prefix(word, candidate), candidate)
        if best is None or key[:2] < best[:2]:
            best = key
    return best[2] if best else None


def _common_prefix(a: str, b: str) -> int:
    count = 0
    for x, y in zip(a.lower(), b.lower()):
        if x != y:
            break
        count += 1
    return count


def did_you_mean(word: str, candidates: Iterable[str]) -> str | None:
    """`did you mean `X`?` for the closest candidate, or None."""
    guess = suggest(word, candidates)
    return f"did you mean `{guess}`?" if guess else None
