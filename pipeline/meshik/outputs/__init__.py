"""Output folders: names proven to stay inside their folder, and outputs committed complete or not at
all (staging, folder swaps)."""
