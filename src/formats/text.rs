//! Reading the text of the field's files: [`read_text`] (the one way a file reaches a reader,
//! refusing devices, pipes, directories and oversized files), and the line, key and number
//! parsing the readers share: a file's lines with its name for errors ([`Source`]), OpenFAST
//! `value Key` lines, numeric tables checked row by row, and Fortran-style numbers.

use crate::error::{Error, Result};
use std::io::Read;
use std::path::Path;

/// Largest file a reader accepts. Real blade files are well under a megabyte; the cap keeps a
/// wrong path (a disk image, a log) from exhausting memory.
pub const MAX_FILE_BYTES: u64 = 64 * 1024 * 1024;

/// The text of a regular file of at most [`MAX_FILE_BYTES`], as UTF-8.
///
/// The file type and size come from the metadata before the file is opened, so a FIFO never
/// blocks and `/dev/zero` is never read; the read itself is capped too, in case the file grows
/// between the two.
pub fn read_text(path: &Path) -> Result<String> {
    let name = path.display().to_string();
    let fail = |message: String| Error::format(name.clone(), 0, message);
    let meta = std::fs::metadata(path).map_err(|e| fail(format!("cannot read: {e}")))?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a directory"
        } else {
            "a device, pipe or socket"
        };
        return Err(fail(format!(
            "cannot read: {kind}, not a regular text file"
        )));
    }
    let too_big = |len: u64| {
        fail(format!(
            "cannot read: {len} bytes is more than the {} MiB a definition file may hold",
            MAX_FILE_BYTES / (1024 * 1024)
        ))
    };
    if meta.len() > MAX_FILE_BYTES {
        return Err(too_big(meta.len()));
    }
    let file = std::fs::File::open(path).map_err(|e| fail(format!("cannot read: {e}")))?;
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| fail(format!("cannot read: {e}")))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_big(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|e| {
        fail(format!(
            "cannot read: not UTF-8 text (invalid byte at offset {}); is this a binary file?",
            e.utf8_error().valid_up_to()
        ))
    })
}

/// A file's lines with its name, so that every error can say where it is. Indices are 0-based
/// inside the readers and become 1-based line numbers in errors.
pub(super) struct Source<'a> {
    pub(super) path: &'a str,
    pub(super) lines: Vec<&'a str>,
    /// Lines starting with this character are comments, skipped like blank lines (AirfoilInfo
    /// files use `!`). `None` where the format has no comment lines, so a stray line inside a
    /// table is an error rather than silently skipped.
    pub(super) comment: Option<char>,
}

/// What a number read by [`Source::bounded`] must be to describe a turbine or a blade.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Bound {
    Any,
    NonNegative,
    Positive,
}

/// A `value  Key  - description` line of an OpenFAST input file.
pub(super) struct KeyLine<'a> {
    pub(super) idx: usize,
    pub(super) key: &'a str,
    pub(super) value: &'a str,
}

/// A table row: its line index and its numbers.
pub(super) struct Row {
    pub(super) idx: usize,
    pub(super) values: Vec<f64>,
}

/// What a table must hold, worded for errors: "expected 49 key-point rows of 4 numbers (kp_xr
/// kp_yr kp_zr initial_twist) in member 1".
pub(super) struct Table {
    pub(super) rows: usize,
    pub(super) what: String,
    pub(super) columns: String,
    /// Where the table belongs, when the file has several ("in member 1").
    pub(super) place: String,
    pub(super) width: usize,
    /// Rows must have exactly `width` values; otherwise at least `width` (Fortran list-directed
    /// reads ignore what follows, e.g. a trailing comment in a HAWC2 ae row).
    pub(super) exact: bool,
}

impl Table {
    pub(super) fn new(rows: usize, what: impl Into<String>, columns: &[&str]) -> Table {
        Table {
            rows,
            what: what.into(),
            columns: columns.join(" "),
            place: String::new(),
            width: columns.len(),
            exact: true,
        }
    }

    pub(super) fn at(mut self, place: impl AsRef<str>) -> Table {
        self.place = format!(" {}", place.as_ref());
        self
    }

    /// Rows may carry more values than the named columns.
    pub(super) fn at_least(mut self) -> Table {
        self.exact = false;
        self
    }

    pub(super) fn expected(&self) -> String {
        let least = if self.exact { "" } else { "at least " };
        let numbers = if self.width == 1 { "number" } else { "numbers" };
        let (what, width, columns, place) = (&self.what, self.width, &self.columns, &self.place);
        match self.rows {
            1 => format!("expected {what}: {least}{width} {numbers} ({columns}){place}"),
            n => format!("expected {n} {what} of {least}{width} {numbers} ({columns}){place}"),
        }
    }
}

impl<'a> Source<'a> {
    pub(super) fn new(path: &'a str, text: &'a str) -> Source<'a> {
        // Windows editors start UTF-8 text with a byte-order mark; it is no part of line 1.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        Source {
            path,
            lines: text.lines().collect(),
            comment: None,
        }
    }

    pub(super) fn with_comments(mut self, marker: char) -> Source<'a> {
        self.comment = Some(marker);
        self
    }

    pub(super) fn err(&self, idx: usize, message: impl Into<String>) -> Error {
        Error::format(self.path, idx + 1, message)
    }

    pub(super) fn err_file(&self, message: impl Into<String>) -> Error {
        Error::format(self.path, 0, message)
    }

    /// Nothing at or after line index `from` is what `expected` describes.
    pub(super) fn missing(&self, expected: &str, from: usize) -> Error {
        self.err_file(match self.lines.len() {
            0 => format!("{expected}, found an empty file"),
            n if from >= n => format!("{expected}, found the end of the file (after line {n})"),
            n => format!("{expected}, found none in lines {}–{n}", from + 1),
        })
    }

    /// The file ended where `expected` was due.
    pub(super) fn eof(&self, expected: &str) -> Error {
        self.missing(expected, self.lines.len())
    }

    /// The first line at or after `from` whose first word is `word` (a table header).
    pub(super) fn line_starting(&self, word: &str, from: usize, expected: &str) -> Result<usize> {
        (from..self.lines.len())
            .find(|&i| {
                self.tokens(i)
                    .first()
                    .is_some_and(|t| t.eq_ignore_ascii_case(word))
            })
            .ok_or_else(|| self.missing(expected, from))
    }

    pub(super) fn line(&self, idx: usize) -> &'a str {
        self.lines.get(idx).copied().unwrap_or("")
    }

    pub(super) fn tokens(&self, idx: usize) -> Vec<&'a str> {
        self.line(idx).split_ascii_whitespace().collect()
    }

    pub(super) fn is_blank(&self, idx: usize) -> bool {
        let t = self.line(idx).trim_ascii_start();
        t.is_empty() || self.comment.is_some_and(|c| t.starts_with(c))
    }

    /// Index of the first line at or after `from` that is neither blank nor a comment.
    pub(super) fn next_content(&self, from: usize) -> Option<usize> {
        (from..self.lines.len()).find(|&i| !self.is_blank(i))
    }

    pub(super) fn expect_content(&self, from: usize, expected: &str) -> Result<usize> {
        self.next_content(from).ok_or_else(|| self.eof(expected))
    }

    /// The next content line, which must be text (a header, a units line, a section rule), not
    /// a row of numbers: a missing header would otherwise swallow the first row unnoticed.
    pub(super) fn expect_text(&self, from: usize, expected: &str) -> Result<usize> {
        let idx = self.expect_content(from, expected)?;
        if numbers(&self.tokens(idx)).is_some() {
            return Err(self.err(idx, format!("{expected}, found a row of numbers")));
        }
        Ok(idx)
    }

    /// The `value  Key` line at `idx`, if it is one.
    pub(super) fn key_line(&self, idx: usize) -> Option<KeyLine<'a>> {
        if self.is_blank(idx) || self.line(idx).trim_ascii_start().starts_with('!') {
            return None;
        }
        let (value, rest) = split_value(self.line(idx))?;
        let key = rest.split_ascii_whitespace().next()?;
        let end = key
            .find(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '_' | '(' | ')')))
            .unwrap_or(key.len());
        Some(KeyLine {
            idx,
            key: &key[..end],
            value,
        })
    }

    /// The first `value  Key` line at or after `from` whose key is one of `keys` (OpenFAST
    /// compares keys case-insensitively; `BldFlDmp(1)` and `BldFlDmp1` are the same key).
    pub(super) fn find_key(&self, keys: &[&str], from: usize) -> Option<KeyLine<'a>> {
        (from..self.lines.len())
            .filter_map(|i| self.key_line(i))
            .find(|k| keys.iter().any(|want| same_key(k.key, want)))
    }

    pub(super) fn key(&self, key: &str, from: usize) -> Result<KeyLine<'a>> {
        self.find_key(&[key], from)
            .ok_or_else(|| self.missing(&format!("expected a line '<value>  {key}'"), from))
    }

    /// The next content line, which must be the `value  Key` line of one of `keys` (for formats
    /// read line by line, where a key further down would belong to something else).
    pub(super) fn key_next(&self, keys: &[&str], from: usize) -> Result<KeyLine<'a>> {
        let expected = format!("expected the line '<value>  {}'", keys.join("' (or '"))
            + if keys.len() > 1 { ")" } else { "" };
        let idx = self.expect_content(from, &expected)?;
        match self.key_line(idx) {
            Some(k) if keys.iter().any(|want| same_key(k.key, want)) => Ok(k),
            _ => Err(self.err(idx, format!("{expected}, found '{}'", self.excerpt(idx)))),
        }
    }

    pub(super) fn number(&self, k: &KeyLine) -> Result<f64> {
        parse_number(k.value).ok_or_else(|| {
            self.err(
                k.idx,
                format!("expected a number for {}, found '{}'", k.key, k.value),
            )
        })
    }

    pub(super) fn count(&self, k: &KeyLine, at_least: usize) -> Result<usize> {
        match k.value.parse::<usize>() {
            Ok(n) if n >= at_least => Ok(n),
            _ => Err(self.err(
                k.idx,
                format!(
                    "expected a whole number of at least {at_least} for {}, found '{}'",
                    k.key, k.value
                ),
            )),
        }
    }

    /// A count, or `None` for OpenFAST's `DEFAULT` (the program's own default applies).
    pub(super) fn count_or_default(&self, k: &KeyLine, at_least: usize) -> Result<Option<usize>> {
        if k.value.eq_ignore_ascii_case("default") {
            return Ok(None);
        }
        self.count(k, at_least).map(Some).map_err(|_| {
            self.err(
                k.idx,
                format!(
                    "expected DEFAULT or a whole number of at least {at_least} for {}, found '{}'",
                    k.key, k.value
                ),
            )
        })
    }

    /// The number on the first `value  key` line at or after `from`, which must lie in `bound`;
    /// an error names the line, the key, the value and what it must be.
    pub(super) fn bounded(&self, key: &str, from: usize, bound: Bound) -> Result<f64> {
        let k = self.key(key, from)?;
        let v = self.number(&k)?;
        let allowed = match bound {
            Bound::NonNegative if v < 0.0 => "at least 0",
            Bound::Positive if v <= 0.0 => "greater than 0",
            _ => return Ok(v),
        };
        Err(self.err(k.idx, format!("{} is {v}: it must be {allowed}", k.key)))
    }

    pub(super) fn flag(&self, k: &KeyLine) -> Result<bool> {
        let v = k.value.trim_matches('.').to_ascii_lowercase();
        match v.as_str() {
            "true" | "t" => Ok(true),
            "false" | "f" => Ok(false),
            _ => Err(self.err(
                k.idx,
                format!("expected True or False for {}, found '{}'", k.key, k.value),
            )),
        }
    }

    /// `table.rows` rows starting at the first content line at or after `from`, blank lines
    /// skipped (Fortran list-directed reads skip them too). Returns the rows and the index
    /// after the last one.
    pub(super) fn rows(&self, from: usize, table: &Table) -> Result<(Vec<Row>, usize)> {
        let mut rows = Vec::new();
        let mut pos = from;
        while rows.len() < table.rows {
            let (row, next) = self.row_after(pos, table, rows.len())?;
            rows.push(row);
            pos = next;
        }
        Ok((rows, pos))
    }

    /// The row of `table` at the first content line at or after `from`, `read` rows of it
    /// already read; returns it and the index after it.
    pub(super) fn row_after(
        &self,
        from: usize,
        table: &Table,
        read: usize,
    ) -> Result<(Row, usize)> {
        let idx = self
            .next_content(from)
            .ok_or_else(|| self.eof(&format!("{} ({read} read)", table.expected())))?;
        Ok((self.row(idx, table)?, idx + 1))
    }

    pub(super) fn row(&self, idx: usize, table: &Table) -> Result<Row> {
        let found = self.line(idx).split_ascii_whitespace().count();
        if found < table.width || (table.exact && found != table.width) {
            return Err(self.err(
                idx,
                format!(
                    "{}, found {found} value(s): '{}'",
                    table.expected(),
                    self.excerpt(idx)
                ),
            ));
        }
        let mut values = Vec::with_capacity(table.width);
        for (col, tok) in self
            .line(idx)
            .split_ascii_whitespace()
            .take(table.width)
            .enumerate()
        {
            let v = parse_number(tok).ok_or_else(|| {
                self.err(
                    idx,
                    format!("{}, found '{tok}' in column {}", table.expected(), col + 1),
                )
            })?;
            values.push(v);
        }
        Ok(Row { idx, values })
    }

    /// Column `col` of `rows` must increase strictly, as every spanwise or angle coordinate the
    /// programs interpolate on must.
    pub(super) fn increasing(&self, rows: &[Row], col: usize, name: &str) -> Result<()> {
        for pair in rows.windows(2) {
            if let [a, b] = pair {
                let (x0, x1) = (value(a, col), value(b, col));
                if x1 <= x0 {
                    return Err(self.err(
                        b.idx,
                        format!(
                            "{name} must increase strictly down the table: {x1} follows {x0} (line {})",
                            a.idx + 1
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The line, shortened for an error message.
    pub(super) fn excerpt(&self, idx: usize) -> String {
        let line = self.line(idx).trim();
        match line.char_indices().nth(60) {
            Some((cut, _)) => format!("{}…", &line[..cut]),
            None => line.to_string(),
        }
    }
}

/// Column `col` of a row (0 outside the row, which the readers rule out by the table width).
pub(super) fn value(row: &Row, col: usize) -> f64 {
    row.values.get(col).copied().unwrap_or(0.0)
}

/// The first `N` values of a row the table reader has already sized to at least `N`.
pub(super) fn array<const N: usize>(values: &[f64]) -> [f64; N] {
    let mut out = [0.0; N];
    for (o, v) in out.iter_mut().zip(values) {
        *o = *v;
    }
    out
}

/// Position of a named column in a table header (OpenFAST names are case-insensitive).
pub(super) fn column(
    src: &Source,
    header: &[&str],
    header_idx: usize,
    name: &str,
) -> Result<usize> {
    header
        .iter()
        .position(|h| h.eq_ignore_ascii_case(name))
        .ok_or_else(|| {
            src.err(
                header_idx,
                format!(
                    "expected a column '{name}' in the table header, found: {}",
                    header.join(" ")
                ),
            )
        })
}

/// Splits `value  rest`: a quoted value (OpenFAST strings, `@"file"` references) up to its
/// closing quote, otherwise the first word.
pub(super) fn split_value(line: &str) -> Option<(&str, &str)> {
    let t = line.trim_ascii_start();
    let quoted = t.strip_prefix('@').unwrap_or(t);
    if let Some(inner) = quoted.strip_prefix('"') {
        let end = inner.find('"')?;
        return Some((&inner[..end], &inner[end + 1..]));
    }
    let end = t.find(|c: char| c.is_ascii_whitespace()).unwrap_or(t.len());
    Some((&t[..end], &t[end..]))
}

pub(super) fn same_key(found: &str, want: &str) -> bool {
    let norm = |s: &str| {
        s.chars()
            .filter(|c| !matches!(c, '(' | ')'))
            .map(|c| c.to_ascii_lowercase())
            .collect::<String>()
    };
    norm(found) == norm(want)
}

/// A finite number, Fortran exponents (`1.0D+00`) included.
pub(super) fn parse_number(tok: &str) -> Option<f64> {
    let v = tok
        .parse::<f64>()
        .ok()
        .or_else(|| tok.replace(['D', 'd'], "E").parse::<f64>().ok())?;
    v.is_finite().then_some(v)
}

/// Every token as a number, or `None` if any is not one (or there are none).
pub(super) fn numbers(tokens: &[&str]) -> Option<Vec<f64>> {
    if tokens.is_empty() {
        return None;
    }
    tokens.iter().map(|t| parse_number(t)).collect()
}

/// A whole number written as a table value (e.g. an airfoil id), at least `at_least`.
pub(super) fn whole(
    src: &Source,
    row: &Row,
    col: usize,
    name: &str,
    at_least: usize,
) -> Result<usize> {
    let v = value(row, col);
    if v.fract() == 0.0 && v >= at_least as f64 && v <= u32::MAX as f64 {
        Ok(v as usize)
    } else {
        Err(src.err(
            row.idx,
            format!("expected {name} to be a whole number of at least {at_least}, found {v}"),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_in_fortran_and_c_notation() {
        assert_eq!(parse_number("1.3308000E+01"), Some(13.308));
        assert_eq!(parse_number("1.0D+00"), Some(1.0));
        assert_eq!(parse_number("-2.5d-1"), Some(-0.25));
        assert_eq!(parse_number("2E+07"), Some(2e7));
        assert_eq!(parse_number("NaN"), None);
        assert_eq!(parse_number("inf"), None);
        assert_eq!(parse_number("DEFAULT"), None);
        assert_eq!(parse_number(""), None);
    }

    #[test]
    fn key_lines_quoted_bare_and_indexed() {
        let text = "\"NRELOffshrBsline5MW_BeamDyn_Blade.dat\"    BldFile - Name of file\n\
                    DEFAULT       tngt_stf_difftol- Maximum\n\
                    0.477465   BldFlDmp(1) - Blade flap mode #1\n\
                    @\"DU21_A17_coords.txt\"    NumCoords ! coords\n\
                    ! 3 NumAlf in a comment\n";
        let src = Source::new("f", text);
        let k = src.key("bldfile", 0).unwrap();
        assert_eq!(
            (k.idx, k.value),
            (0, "NRELOffshrBsline5MW_BeamDyn_Blade.dat")
        );
        let k = src.key("tngt_stf_difftol", 0).unwrap();
        assert_eq!(src.count_or_default(&k, 1).unwrap(), None);
        let k = src.key("BldFlDmp1", 0).unwrap();
        assert_eq!(src.number(&k).unwrap(), 0.477465);
        assert_eq!(
            src.key("NumCoords", 0).unwrap().value,
            "DU21_A17_coords.txt"
        );
        let e = src.key("NumAlf", 0).err().unwrap();
        assert!(e.to_string().contains("NumAlf"), "{e}");
    }

    #[test]
    fn rows_name_the_line_the_column_and_the_table() {
        let src = Source::new("f.dat", "1 2 3 4\n\n5 6 abc 8\n");
        let table = Table::new(2, "key-point rows", &["a", "b", "c", "d"]);
        let e = src.rows(0, &table).err().unwrap();
        assert_eq!(
            e.to_string(),
            "f.dat:3: expected 2 key-point rows of 4 numbers (a b c d), found 'abc' in column 3"
        );
        let e = Source::new("f.dat", "1 2 3 4\n")
            .rows(0, &table)
            .err()
            .unwrap();
        assert!(e
            .to_string()
            .contains("(1 read), found the end of the file (after line 1)"));
    }
}
