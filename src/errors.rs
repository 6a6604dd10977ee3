//! What every room's errors share: an error and its causes on one line, as `cosco` prints
//! it, the Python package raises it and the evaluator keeps a fold's reason.

/// An error and its causes on one line, leaving out causes whose text the message above
/// already contains (many errors quote their cause): what `cosco` prints after `Error: `, and
/// the message of the Python package's exceptions.
pub fn error_line(e: &(dyn std::error::Error + 'static)) -> String {
    let mut line = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        let text = c.to_string();
        if !line.contains(&text) {
            line.push_str(": ");
            line.push_str(&text);
        }
        cause = c.source();
    }
    line
}
