"""Exporting: Draco frames, the animated .glb in its three variants, and how far they decode from
the solver's frames."""
