//! Save and load: the model types' serde description ([`Hsom`], and
//! [`GestureModel`](super::GestureModel) of its branches) in two forms generated from it,
//! binary (`.bin`: bincode, fixed-width little-endian integers) and text (`.txt`: JSON), each
//! behind a header (magic, format version, kind of model) that is read first and followed by
//! an FNV-1a checksum; written atomically. A file is decoded (every length it claims backed
//! by its bytes), then every shape and value is checked against its embedded configuration,
//! then its checksum.
//!
//! Binary: `COSCOHSM`, the version (u32), the kind (two bytes: one gesture 1 or several 2;
//! paper 0 or events 1), the model, the checksum (u64) of everything before it. Text: the
//! lines `cosco-hsom model`, `version N`, `kind one-gesture events` (or `one-gesture paper`,
//! `several-gestures events`), the model as one line of JSON, `checksum HEX`.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::config::Algorithm;
use crate::fsutil::write_atomic;

use super::errors::PersistError;
use super::events::trace_places;
use super::model::{Algo, EventsHsom, GestureModel, Hsom, Model, Part};

/// Magic bytes opening a binary model file.
const MAGIC: &[u8; 8] = b"COSCOHSM";
/// First line of a plain-text model file.
const TEXT_MAGIC: &str = "cosco-hsom model";
/// Format version of model files, of one gesture or several (the header says which).
pub const FORMAT_VERSION: u32 = 27;
/// The oldest version read: a file of several gestures older than [`FORMAT_VERSION`] holds
/// thresholds calibrated on the unweighed score, so it loads and reproduces, and recognition
/// asks for it to be retrained ([`GestureError::Recalibrate`](super::GestureError)).
const OLDEST_READ: u32 = 26;
/// The most bytes a model file may hold (what bincode may be asked to read).
const MAX_MODEL_BYTES: usize = 1 << 30;

/// What a model file holds: one gesture (of an algorithm) or several (the events extension).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    One(Algorithm),
    Several,
}

impl Kind {
    const ALL: [Kind; 3] = [
        Kind::One(Algorithm::Paper),
        Kind::One(Algorithm::Events),
        Kind::Several,
    ];
    fn bytes(self) -> [u8; 2] {
        match self {
            Kind::One(Algorithm::Paper) => [1, 0],
            Kind::One(Algorithm::Events) => [1, 1],
            Kind::Several => [2, 1],
        }
    }
    fn word(self) -> &'static str {
        match self {
            Kind::One(Algorithm::Paper) => "one-gesture paper",
            Kind::One(Algorithm::Events) => "one-gesture events",
            Kind::Several => "several-gestures events",
        }
    }
}

/// The file's form, from its extension.
#[derive(Debug, Clone, Copy)]
enum Format {
    Bin,
    Txt,
}

fn ext(path: &Path) -> Result<Format, PersistError> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
    {
        Some(e) if e == "bin" => Ok(Format::Bin),
        Some(e) if e == "txt" => Ok(Format::Txt),
        _ => Err(PersistError::UnknownExtension {
            path: path.to_path_buf(),
        }),
    }
}

fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

fn bincode_config() -> impl bincode::config::Config {
    bincode::config::standard()
        .with_little_endian()
        .with_fixed_int_encoding()
        .with_limit::<MAX_MODEL_BYTES>()
}

fn corrupted(path: &Path, what: String) -> PersistError {
    PersistError::Corrupted {
        path: path.to_path_buf(),
        what,
    }
}

/// `line` quoted, at most its first 40 characters (a model's line is kilobytes long).
fn quoted(line: &str) -> String {
    match line.char_indices().nth(40) {
        Some((i, _)) => format!("{:?}...", &line[..i]),
        None => format!("{line:?}"),
    }
}

/// What bincode could not decode, in words (its own text is its debug form).
fn decode_error(e: bincode::error::DecodeError) -> String {
    use bincode::error::DecodeError as E;
    match e {
        // serde's words: a value the description refuses, a map of the wrong size, ...
        E::OtherString(s) => s,
        E::Other(s) => s.to_string(),
        E::UnexpectedVariant {
            type_name, found, ..
        } => format!("variant {found} of {type_name}, which has no such variant"),
        E::InvalidBooleanValue(v) => format!("a yes-or-no byte of {v}, where 0 or 1 is allowed"),
        E::Utf8 { .. } | E::InvalidCharEncoding(_) => "a text that is not UTF-8".into(),
        E::OutsideUsizeRange(v) => format!("a length of {v}, beyond what this machine can hold"),
        _ => "bytes that are not a model of this format".into(),
    }
}

fn truncated(path: &Path, what: &str) -> PersistError {
    PersistError::Truncated {
        path: path.to_path_buf(),
        what: what.to_string(),
    }
}

/// `value` of `kind` in the form `fmt`: header, model, checksum.
fn encode<T: Serialize>(kind: Kind, value: &T, fmt: Format) -> Vec<u8> {
    match fmt {
        Format::Bin => {
            let mut b = MAGIC.to_vec();
            b.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
            b.extend_from_slice(&kind.bytes());
            // cannot fail: every type of the description serialises (no map keys, no
            // unknown lengths), and a model is far below the limit
            let body = bincode::serde::encode_to_vec(value, bincode_config()).unwrap_or_default();
            b.extend_from_slice(&body);
            let sum = fnv1a(&b);
            b.extend_from_slice(&sum.to_le_bytes());
            b
        }
        Format::Txt => {
            // cannot fail: the description has no map with non-string keys
            let json = serde_json::to_string(value).unwrap_or_default();
            let mut s = format!(
                "{TEXT_MAGIC}\nversion {FORMAT_VERSION}\nkind {}\n{json}\n",
                kind.word()
            );
            let sum = fnv1a(s.as_bytes());
            s.push_str(&format!("checksum {sum:016x}\n"));
            s.into_bytes()
        }
    }
}

/// A model file whose header was read: its kind, its model's bytes, and the checksum.
struct Opened<'a> {
    kind: Kind,
    version: u32,
    fmt: Format,
    body: &'a [u8],
    signed: &'a [u8],
    stored: u64,
    path: &'a Path,
}

/// Read the header of `bytes` (a file of form `fmt`): magic, then version (older: the
/// "retrain" error; newer: "written by a newer version"), then kind, before anything else.
fn open<'a>(bytes: &'a [u8], fmt: Format, path: &'a Path) -> Result<Opened<'a>, PersistError> {
    let version = |found: u32| match found {
        v if (OLDEST_READ..=FORMAT_VERSION).contains(&v) => Ok(v),
        v if v < OLDEST_READ => Err(PersistError::Version {
            path: path.to_path_buf(),
            found: v,
            expected: FORMAT_VERSION,
        }),
        v => Err(PersistError::Newer {
            path: path.to_path_buf(),
            found: v,
            expected: FORMAT_VERSION,
        }),
    };
    let bad_kind = |k: String| {
        corrupted(
            path,
            format!(
                "kind line {k}; known: kind {}",
                Kind::ALL.map(|k| k.word()).join(", kind ")
            ),
        )
    };
    match fmt {
        Format::Bin => {
            if bytes.len() < 12 || &bytes[..8] != MAGIC {
                return Err(PersistError::BadMagic {
                    path: path.to_path_buf(),
                });
            }
            let version = version(u32::from_le_bytes([
                bytes[8], bytes[9], bytes[10], bytes[11],
            ]))?;
            if bytes.len() < 14 + 8 {
                return Err(truncated(path, "header"));
            }
            let kb = [bytes[12], bytes[13]];
            let kind = Kind::ALL
                .into_iter()
                .find(|k| k.bytes() == kb)
                .ok_or_else(|| bad_kind(format!("{kb:?}")))?;
            let (signed, sum) = bytes.split_at(bytes.len() - 8);
            let mut stored = [0u8; 8];
            stored.copy_from_slice(sum);
            Ok(Opened {
                kind,
                version,
                fmt,
                body: &signed[14..],
                signed,
                stored: u64::from_le_bytes(stored),
                path,
            })
        }
        Format::Txt => {
            let text = std::str::from_utf8(bytes).map_err(|_| PersistError::BadMagic {
                path: path.to_path_buf(),
            })?;
            let mut lines = text.split_inclusive('\n');
            let mut head = 0usize;
            let mut next = |what: &str| {
                let l = lines.next().ok_or_else(|| truncated(path, what))?;
                head += l.len();
                Ok::<&str, PersistError>(l.trim_end())
            };
            if next("format line").ok() != Some(TEXT_MAGIC) {
                return Err(PersistError::BadMagic {
                    path: path.to_path_buf(),
                });
            }
            let l = next("version line")?;
            let found = l
                .strip_prefix("version ")
                .and_then(|v| v.trim().parse::<u32>().ok())
                .ok_or_else(|| corrupted(path, format!("bad version line {}", quoted(l))))?;
            let version = version(found)?;
            let l = next("kind line")?;
            let word = l.strip_prefix("kind ").unwrap_or("");
            let kind = Kind::ALL
                .into_iter()
                .find(|k| k.word() == word)
                .ok_or_else(|| bad_kind(quoted(l)))?;
            // the checksum is the last line, over everything before it
            let body_end = text.trim_end_matches('\n').rfind('\n').map_or(0, |i| i + 1);
            let stored = text[body_end..]
                .trim()
                .strip_prefix("checksum ")
                .and_then(|h| u64::from_str_radix(h.trim(), 16).ok())
                .filter(|_| body_end >= head)
                .ok_or_else(|| truncated(path, "checksum line missing"))?;
            let signed = &bytes[..body_end];
            Ok(Opened {
                kind,
                version,
                fmt,
                body: &signed[head..],
                signed,
                stored,
                path,
            })
        }
    }
}

impl Opened<'_> {
    /// The model the file holds, decoded (not yet checked).
    fn decode<T: for<'de> Deserialize<'de>>(&self) -> Result<T, PersistError> {
        match self.fmt {
            Format::Bin => {
                use bincode::error::DecodeError;
                let (v, read) =
                    bincode::serde::borrow_decode_from_slice(self.body, bincode_config()).map_err(
                        |e| match e {
                            DecodeError::UnexpectedEnd { .. } | DecodeError::LimitExceeded => {
                                truncated(self.path, "the model ends early")
                            }
                            e => corrupted(self.path, decode_error(e)),
                        },
                    )?;
                if read != self.body.len() {
                    return Err(corrupted(
                        self.path,
                        format!("{} unexpected bytes at the end", self.body.len() - read),
                    ));
                }
                Ok(v)
            }
            Format::Txt => {
                // cannot fail: `open` found the body in a UTF-8 text
                let text = std::str::from_utf8(self.body).unwrap_or_default();
                serde_json::from_str(text).map_err(|e| {
                    if e.is_eof() {
                        truncated(self.path, "the model ends early")
                    } else {
                        corrupted(self.path, e.to_string())
                    }
                })
            }
        }
    }

    /// The checksum over everything before it.
    fn verify(&self) -> Result<(), PersistError> {
        if fnv1a(self.signed) != self.stored {
            return Err(corrupted(self.path, "checksum mismatch".into()));
        }
        Ok(())
    }

    /// Refuse another kind than `want`.
    fn expect(&self, want: &[Kind]) -> Result<(), PersistError> {
        if want.contains(&self.kind) {
            return Ok(());
        }
        Err(PersistError::Kind {
            path: self.path.to_path_buf(),
            found: self.kind.word().to_string(),
            expected: want
                .iter()
                .map(|k| k.word())
                .collect::<Vec<_>>()
                .join(" or "),
        })
    }
}

/// The bytes one part of a model takes in its binary file ([`Hsom::file_parts`]).
#[derive(Debug, Clone, PartialEq)]
pub struct FilePart {
    /// What the part holds.
    pub part: &'static str,
    /// Its bytes in the binary form.
    pub bytes: usize,
}

/// The bytes `value` takes in the binary form.
fn binary_len<T: Serialize + ?Sized>(value: &T) -> usize {
    bincode::serde::encode_to_vec(value, bincode_config()).map_or(0, |b| b.len())
}

impl<A: Part> Model<A> {
    /// The binary file's bytes by part, in file order grouped by what they hold; they add up
    /// to the file's length (docs/BENCHMARKS.md, "The model file").
    pub(crate) fn file_parts(&self) -> Vec<FilePart> {
        const NODES: &str = "per-node statistics (hits, ends, dwell, followers, exemplars)";
        const LEVELS: &str = "per-level statistics, normalisation, lengths, columns";
        const PLACES: &str = "postures and end postures";
        let mut fields = vec![
            ("configuration (XML)", binary_len(&self.config)),
            (LEVELS, binary_len(&self.offset)),
            (LEVELS, binary_len(&self.scale)),
            (LEVELS, binary_len(&self.trained)),
            (NODES, binary_len(&self.hits)),
            (LEVELS, binary_len(&self.qe)),
            (LEVELS, binary_len(&self.te)),
            (LEVELS, binary_len(&self.demo_len)),
            (LEVELS, binary_len(&self.demo_runs)),
            (NODES, binary_len(&self.dwell)),
            (LEVELS, binary_len(&self.columns)),
            (LEVELS, binary_len(&self.accuracy)),
            (LEVELS, binary_len(&self.lookup)),
            // the algorithm's tag
            (LEVELS, 4),
        ];
        match self.part.tagged() {
            Algo::Paper(m) => fields.push((NODES, binary_len(&m.end_hits))),
            Algo::Events(e) => fields.extend([
                (LEVELS, binary_len(&e.threshold)),
                (LEVELS, binary_len(&e.heldout_accuracy)),
                (LEVELS, binary_len(&e.heldout_lookup)),
                (NODES, binary_len(&e.followers)),
                (NODES, binary_len(&e.follower_at)),
                (NODES, binary_len(&e.exemplar_phase)),
                (NODES, binary_len(&e.exemplars)),
                (PLACES, binary_len(&e.knots)),
                ("start placements", binary_len(&e.start_knots)),
                ("start placements", binary_len(&e.start_posture)),
                (LEVELS, binary_len(&e.demo_smoothness)),
                (LEVELS, binary_len(&e.start_fade)),
                (PLACES, binary_len(&e.end_posture)),
                ("traced chunks", binary_len(&e.traces)),
            ]),
        }
        fields.push((
            "kept demonstrations (the band, updates)",
            binary_len(&self.paths) + binary_len(&self.kept),
        ));
        fields.push(("weights", binary_len(&self.maps)));
        let mut parts = vec![FilePart {
            part: "header and checksum",
            bytes: MAGIC.len() + 4 + 2 + 8,
        }];
        for (part, bytes) in fields {
            match parts.iter_mut().find(|p| p.part == part) {
                Some(p) => p.bytes += bytes,
                None => parts.push(FilePart { part, bytes }),
            }
        }
        parts
    }
}

impl EventsHsom {
    /// The most bytes the traced chunks may take in the binary form: every node of every
    /// traced level with all its chunks, a bound set by the configuration alone.
    pub(crate) fn traced_ceiling(&self) -> usize {
        let p = self.config.params();
        let Some(t) = &self.part.traces else {
            return 0;
        };
        let (k, s) = (p.memory, trace_places(p));
        let chunks: usize = (1..t.levels.len())
            .filter(|&l| super::events::trace_words(k, l, s, self.maps[l].len()) > 0)
            .map(|l| {
                let width = super::events::trace_width(k, l, s).unwrap_or(0);
                // each chunk: its node (4), its words' count (8) and words (4 each)
                self.maps[l].len() * super::events::TRACED_CHUNKS * (4 + 8 + 4 * width)
            })
            .sum();
        // the option's tag, the levels' count and each level's count
        1 + 8 + 8 * t.levels.len() + chunks
    }
}

/// A model type with files of its own: the kinds it reads, and how it is written and
/// checked.
trait ModelFile: Serialize + Sized {
    /// The kinds of file it loads from.
    const READS: &'static [Kind];
    /// The kind of file it is saved as.
    fn file_kind(&self) -> Kind;
    /// Its file in the form `fmt`.
    fn write(&self, fmt: Format) -> Vec<u8> {
        encode(self.file_kind(), self, fmt)
    }
    /// The model of `file` (of a kind in `READS`), decoded and every shape and value checked.
    fn decode_checked(file: &Opened<'_>) -> Result<Self, PersistError>;
}

/// Read a file of form `fmt` with every check; `path` only names it in errors.
fn read_form<T: ModelFile>(bytes: &[u8], fmt: Format, path: &Path) -> Result<T, PersistError> {
    let file = open(bytes, fmt, path)?;
    file.expect(T::READS)?;
    let model = T::decode_checked(&file)?;
    file.verify()?;
    Ok(model)
}

impl ModelFile for Hsom {
    const READS: &'static [Kind] = &[Kind::One(Algorithm::Paper), Kind::One(Algorithm::Events)];

    fn file_kind(&self) -> Kind {
        Kind::One(self.config().params().kind())
    }

    fn decode_checked(file: &Opened<'_>) -> Result<Hsom, PersistError> {
        let model: Hsom = file.decode()?;
        if file.kind != model.file_kind() {
            return Err(corrupted(
                file.path,
                format!(
                    "the header says {}, the configuration algorithm {}",
                    file.kind.word(),
                    model.config().params().kind().name()
                ),
            ));
        }
        model.check().map_err(|what| corrupted(file.path, what))?;
        Ok(model)
    }
}

impl ModelFile for GestureModel {
    const READS: &'static [Kind] = &[
        Kind::One(Algorithm::Paper),
        Kind::One(Algorithm::Events),
        Kind::Several,
    ];

    fn file_kind(&self) -> Kind {
        match self.labels.is_empty() {
            true => self.branches[0].file_kind(),
            false => Kind::Several,
        }
    }

    /// A single-gesture model is written exactly as its [`Hsom`].
    fn write(&self, fmt: Format) -> Vec<u8> {
        match self.labels.is_empty() {
            true => self.branches[0].write(fmt),
            false => encode(Kind::Several, self, fmt),
        }
    }

    fn decode_checked(file: &Opened<'_>) -> Result<GestureModel, PersistError> {
        if file.kind != Kind::Several {
            return Ok(Hsom::decode_checked(file)?.into());
        }
        let mut model: GestureModel = file.decode()?;
        model.check().map_err(|what| corrupted(file.path, what))?;
        if file.version < FORMAT_VERSION {
            // thresholds of another score: recognition refuses until retrained
            model.calibration.clear();
        }
        Ok(model)
    }
}

/// Saving, loading and the two forms in memory, written once for both model types.
macro_rules! model_files {
    ($t:ty) => {
        impl $t {
            /// Save to `path`: binary for `.bin`, plain text for `.txt` (atomic write); a
            /// single gesture as one gesture's file. The bytes are read back with every
            /// check of loading first: a model that could not be loaded is refused here, and
            /// nothing is written.
            pub fn save(&self, path: &Path) -> Result<(), PersistError> {
                let fmt = ext(path)?;
                let bytes = self.write(fmt);
                read_form::<Self>(&bytes, fmt, path)?;
                write_atomic(path, &bytes).map_err(|source| PersistError::Io {
                    path: path.to_path_buf(),
                    source,
                })
            }

            /// Load a model saved by `save`; the form is chosen by the extension, the kind
            /// read from the header.
            pub fn load(path: &Path) -> Result<Self, PersistError> {
                let fmt = ext(path)?;
                let bytes = std::fs::read(path).map_err(|source| PersistError::Io {
                    path: path.to_path_buf(),
                    source,
                })?;
                read_form(&bytes, fmt, path)
            }

            /// The binary form (header, model, checksum).
            pub fn to_bytes(&self) -> Vec<u8> {
                self.write(Format::Bin)
            }

            /// Read the binary form; `path` only names the file in errors.
            pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<Self, PersistError> {
                read_form(bytes, Format::Bin, path)
            }

            /// The plain-text form: the header lines, the model as JSON, a checksum line.
            pub fn to_text(&self) -> String {
                // cannot fail: the text form is ASCII lines and JSON
                String::from_utf8(self.write(Format::Txt)).unwrap_or_default()
            }

            /// Read the plain-text form; `path` only names the file in errors.
            pub fn from_text(text: &str, path: &Path) -> Result<Self, PersistError> {
                read_form(text.as_bytes(), Format::Txt, path)
            }
        }
    };
}

model_files!(Hsom);
model_files!(GestureModel);

#[cfg(test)]
mod tests;
