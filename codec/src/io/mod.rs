//! Mesh file readers and writers.
