"""Pure, vectorised physics kernels (no object state beyond the profile passed in)."""
