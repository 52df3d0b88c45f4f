//! Readers and writers at the edge (SVG pictures of 2D trees).
