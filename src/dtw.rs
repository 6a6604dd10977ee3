//! Dynamic time warping.
