"""Posing: simplifying an example set, posing every frame of an animation with the core, blending
examples, and the example sets a worker keeps between jobs."""
