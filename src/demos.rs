//! Demonstration CSV files.
