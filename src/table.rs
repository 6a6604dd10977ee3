//! Markdown tables, as every report, study and example prints them: a header line, a `|---|`
//! separator with one `---|` a column, then one line a row. A cell is written `| text |`
//! (an empty one `| |`); every line ends with a line break.
//!
//! ```
//! use cosco_hsom::table::Table;
//! let mut t = Table::new(["gesture", "joint DTW", "note"]);
//! t.row(["wave", "0.0123", ""]);
//! assert_eq!(
//!     t.to_string(),
//!     "| gesture | joint DTW | note |\n|---|---|---|\n| wave | 0.0123 | |\n"
//! );
//! // a table printed a row at a time: the header first, then each line as it comes
//! assert_eq!(Table::new(["a", "b"]).to_string(), "| a | b |\n|---|---|\n");
//! assert_eq!(Table::line(["1", "2"]), "| 1 | 2 |\n");
//! ```

use std::fmt::{self, Write as _};

/// A Markdown table: header cells and rows of cells (a row may have another number of cells
/// than the header; it is written as given).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these header cells and no rows yet.
    pub fn new<S: ToString>(header: impl IntoIterator<Item = S>) -> Table {
        Table {
            header: header.into_iter().map(|c| c.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Add a row of cells.
    pub fn row<S: ToString>(&mut self, cells: impl IntoIterator<Item = S>) -> &mut Table {
        self.rows
            .push(cells.into_iter().map(|c| c.to_string()).collect());
        self
    }

    /// How many rows (the header aside).
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether the table has no rows.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// One row's line, line break included: for a table printed a row at a time after its
    /// header (a [`Table`] without rows).
    pub fn line<S: ToString>(cells: impl IntoIterator<Item = S>) -> String {
        let mut s = String::new();
        // cannot fail: writing to a String
        let _ = write_line(&mut s, cells.into_iter().map(|c| c.to_string()));
        s
    }
}

fn write_line<S: AsRef<str>>(
    f: &mut impl fmt::Write,
    cells: impl IntoIterator<Item = S>,
) -> fmt::Result {
    f.write_char('|')?;
    for c in cells {
        let c = c.as_ref();
        if c.is_empty() {
            f.write_str(" |")?;
        } else {
            write!(f, " {c} |")?;
        }
    }
    f.write_char('\n')
}

impl fmt::Display for Table {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_line(f, &self.header)?;
        f.write_char('|')?;
        for _ in &self.header {
            f.write_str("---|")?;
        }
        f.write_char('\n')?;
        for r in &self.rows {
            write_line(f, r)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
