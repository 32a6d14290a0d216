"""Processing algorithms, one per module named after its id; each a thin adapter over core."""
