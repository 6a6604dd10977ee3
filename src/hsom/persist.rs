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
use super::followers::FOLLOWERS;
use super::model::{input_dim, Algo, Hsom};

/// Magic bytes opening a binary model file.
const MAGIC: &[u8; 8] = b"COSCOHSM";
/// First line of a plain-text model file.
const TEXT_MAGIC: &str = "cosco-hsom model";
/// Format version of model files, of one gesture or several (the header says which).
pub const FORMAT_VERSION: u32 = 24;
/// The most bytes a model file may hold (what bincode may be asked to read).
const MAX_MODEL_BYTES: usize = 1 << 30;
/// The longest demonstration a model file may record, samples (a day at 1 kHz): the
/// reproduction's length cap derives from it.
const MAX_DEMO_SAMPLES: f64 = 1e8;

/// What a model file holds: one gesture (of an algorithm) or several (the events extension).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
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
pub(super) enum Format {
    Bin,
    Txt,
}

pub(super) fn ext(path: &Path) -> Result<Format, PersistError> {
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

fn truncated(path: &Path, what: &str) -> PersistError {
    PersistError::Truncated {
        path: path.to_path_buf(),
        what: what.to_string(),
    }
}

/// `value` of `kind` in the form `fmt`: header, model, checksum.
pub(super) fn encode<T: Serialize>(kind: Kind, value: &T, fmt: Format) -> Vec<u8> {
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
pub(super) struct Opened<'a> {
    pub(super) kind: Kind,
    fmt: Format,
    body: &'a [u8],
    signed: &'a [u8],
    stored: u64,
    path: &'a Path,
}

/// Read the header of `bytes` (a file of form `fmt`): magic, then version (older: the
/// "retrain" error; newer: "written by a newer version"), then kind, before anything else.
pub(super) fn open<'a>(
    bytes: &'a [u8],
    fmt: Format,
    path: &'a Path,
) -> Result<Opened<'a>, PersistError> {
    let version = |found: u32| match found {
        v if v == FORMAT_VERSION => Ok(()),
        v if v < FORMAT_VERSION => Err(PersistError::Version {
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
    let bad_kind = |k: &dyn std::fmt::Debug| {
        corrupted(
            path,
            format!(
                "kind {k:?}; known: {}",
                Kind::ALL.map(|k| k.word()).join(", ")
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
            version(u32::from_le_bytes([
                bytes[8], bytes[9], bytes[10], bytes[11],
            ]))?;
            if bytes.len() < 14 + 8 {
                return Err(truncated(path, "header"));
            }
            let kb = [bytes[12], bytes[13]];
            let kind = Kind::ALL
                .into_iter()
                .find(|k| k.bytes() == kb)
                .ok_or_else(|| bad_kind(&kb))?;
            let (signed, sum) = bytes.split_at(bytes.len() - 8);
            let mut stored = [0u8; 8];
            stored.copy_from_slice(sum);
            Ok(Opened {
                kind,
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
                .ok_or_else(|| corrupted(path, format!("bad version line {l:.40?}")))?;
            version(found)?;
            let l = next("kind line")?;
            let word = l.strip_prefix("kind ").unwrap_or("");
            let kind = Kind::ALL
                .into_iter()
                .find(|k| k.word() == word)
                .ok_or_else(|| bad_kind(&l))?;
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
    pub(super) fn decode<T: for<'de> Deserialize<'de>>(&self) -> Result<T, PersistError> {
        match self.fmt {
            Format::Bin => {
                use bincode::error::DecodeError;
                let (v, read) =
                    bincode::serde::borrow_decode_from_slice(self.body, bincode_config()).map_err(
                        |e| match e {
                            DecodeError::UnexpectedEnd { .. } | DecodeError::LimitExceeded => {
                                truncated(self.path, "the model ends early")
                            }
                            e => corrupted(self.path, e.to_string()),
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
    pub(super) fn verify(&self) -> Result<(), PersistError> {
        if fnv1a(self.signed) != self.stored {
            return Err(corrupted(self.path, "checksum mismatch".into()));
        }
        Ok(())
    }

    /// Refuse another kind than `want`.
    pub(super) fn expect(&self, want: &[Kind]) -> Result<(), PersistError> {
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

impl Hsom {
    /// The binary file's bytes by part, in file order grouped by what they hold; they add up
    /// to the file's length (docs/BENCHMARKS.md, "The model file").
    pub fn file_parts(&self) -> Vec<FilePart> {
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
        match &self.algo {
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

    /// The most bytes the traced chunks may take in the binary form: every node of every
    /// traced level with all its chunks, a bound set by the configuration alone.
    pub fn traced_ceiling(&self) -> usize {
        let p = self.config.params();
        let Some(t) = &self.ev().traces else {
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

/// A model type with files of its own: its kind, and how a file is read back.
pub(super) trait ModelFile: Serialize + Sized {
    /// The kind of file it is saved as.
    fn file_kind(&self) -> Kind;
    /// Read a file of form `fmt` with every check; `path` only names it in errors.
    fn read_form(bytes: &[u8], fmt: Format, path: &Path) -> Result<Self, PersistError>;
}

/// Save `model` to `path` (the form by the extension; atomic). The bytes are read back with
/// every check of loading first: a model that could not be loaded is refused, and nothing
/// is written.
pub(super) fn save<T: ModelFile>(model: &T, path: &Path) -> Result<(), PersistError> {
    let fmt = ext(path)?;
    let bytes = encode(model.file_kind(), model, fmt);
    T::read_form(&bytes, fmt, path)?;
    write_atomic(path, &bytes).map_err(|source| PersistError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Load a model of type `T` from `path` (the form by the extension).
pub(super) fn load<T: ModelFile>(path: &Path) -> Result<T, PersistError> {
    let fmt = ext(path)?;
    let bytes = std::fs::read(path).map_err(|source| PersistError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    T::read_form(&bytes, fmt, path)
}

/// The text form of `model`.
pub(super) fn text<T: ModelFile>(model: &T) -> String {
    // cannot fail: the text form is ASCII lines and JSON
    String::from_utf8(encode(model.file_kind(), model, Format::Txt)).unwrap_or_default()
}

impl ModelFile for Hsom {
    fn file_kind(&self) -> Kind {
        Kind::One(self.config.params().kind())
    }

    fn read_form(bytes: &[u8], fmt: Format, path: &Path) -> Result<Hsom, PersistError> {
        let file = open(bytes, fmt, path)?;
        file.expect(&[Kind::One(Algorithm::Paper), Kind::One(Algorithm::Events)])?;
        let model: Hsom = file.decode()?;
        model.check(file.kind, path)?;
        file.verify()?;
        Ok(model)
    }
}

impl Hsom {
    /// Save to `path`: binary for `.bin`, plain text for `.txt` (atomic write). The bytes are
    /// read back with every check of [`Hsom::load`] first: a model that could not be loaded
    /// is refused here, and nothing is written.
    pub fn save(&self, path: &Path) -> Result<(), PersistError> {
        save(self, path)
    }

    /// Load a model saved by [`Hsom::save`]; the form is chosen by the extension.
    pub fn load(path: &Path) -> Result<Hsom, PersistError> {
        load(path)
    }

    /// The binary form (header, model, checksum).
    pub fn to_bytes(&self) -> Vec<u8> {
        encode(self.file_kind(), self, Format::Bin)
    }

    /// Read the binary form; `path` is only used in error messages.
    pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<Hsom, PersistError> {
        Hsom::read_form(bytes, Format::Bin, path)
    }

    /// The plain-text form: the header lines, the model as JSON, a checksum line.
    pub fn to_text(&self) -> String {
        text(self)
    }

    /// Read the plain-text form; `path` is only used in error messages.
    pub fn from_text(text: &str, path: &Path) -> Result<Hsom, PersistError> {
        Hsom::read_form(text.as_bytes(), Format::Txt, path)
    }

    /// Every shape and value of a model read from a file (of kind `kind`) against its
    /// embedded configuration.
    pub(super) fn check(&self, kind: Kind, path: &Path) -> Result<(), PersistError> {
        let bad = |what: String| Err(corrupted(path, what));
        let p = self.config.params();
        if kind != Kind::Several && kind != self.file_kind() {
            return bad(format!(
                "the header says {}, the configuration algorithm {}",
                kind.word(),
                p.kind().name()
            ));
        }
        let holds = match self.algo {
            Algo::Paper(_) => Algorithm::Paper,
            Algo::Events(_) => Algorithm::Events,
        };
        if holds != p.kind() {
            return bad(format!(
                "the model holds the {} algorithm's part, the configuration algorithm {}",
                holds.name(),
                p.kind().name()
            ));
        }
        let height = p.levels.len();
        if self.maps.len() != height {
            return bad(format!(
                "{} levels, the configuration has {height}",
                self.maps.len()
            ));
        }
        for (l, (m, lp)) in self.maps.iter().zip(&p.levels).enumerate() {
            let dim = input_dim(&self.config, l);
            if (m.rows(), m.cols(), m.dim()) != (lp.rows, lp.cols, dim)
                || m.topology() != lp.topology
            {
                return bad(format!(
                    "level {l} is {}x{} of dimension {} ({}), the configuration says {}x{} of dimension {dim} ({})",
                    m.rows(),
                    m.cols(),
                    m.dim(),
                    m.topology().name(),
                    lp.rows,
                    lp.cols,
                    lp.topology.name()
                ));
            }
        }
        let nodes: Vec<usize> = self.maps.iter().map(|m| m.len()).collect();
        let (n0, state, k) = (nodes[0], p.state_length, p.memory);
        let per_level = |name: &str, lens: Vec<usize>, per_node: usize, extra: usize| {
            (0..height.max(lens.len()))
                .map(|l| {
                    let want = nodes.get(l).map_or(0, |n| (n + extra) * per_node);
                    (
                        format!("{name} of level {l}"),
                        lens.get(l).copied().unwrap_or(0),
                        want,
                    )
                })
                .collect::<Vec<_>>()
        };
        fn lens<T>(v: &[Vec<T>]) -> Vec<usize> {
            v.iter().map(Vec::len).collect()
        }
        let mut sizes: Vec<(&str, usize, usize)> = vec![
            ("training counts", self.trained.len(), height),
            ("quantization errors", self.qe.len(), height),
            ("topographic errors", self.te.len(), height),
            ("hit counts", self.hits.len(), height),
            ("offset", self.offset.len(), state),
            ("scale", self.scale.len(), state),
            ("dwell", self.dwell.len(), n0),
            ("accuracy", self.accuracy.len(), height),
            ("lookup accuracy", self.lookup.len(), height),
            ("column names", self.columns.len(), state),
        ];
        let mut sizes: Vec<(String, usize, usize)> = match &self.algo {
            Algo::Paper(m) => {
                sizes.push(("end nodes", m.end_hits.len(), n0));
                sizes
                    .into_iter()
                    .map(|(n, a, b)| (n.to_string(), a, b))
                    .collect()
            }
            Algo::Events(e) => {
                sizes.extend([
                    ("match thresholds", e.threshold.len(), height),
                    ("held-out accuracy", e.heldout_accuracy.len(), height),
                    ("held-out lookup accuracy", e.heldout_lookup.len(), height),
                    (
                        "follower positions",
                        e.follower_at.len(),
                        (n0 + 1) * FOLLOWERS,
                    ),
                    ("followers", e.followers.len(), height),
                    ("exemplars", e.exemplars.len(), height),
                    ("exemplar positions", e.exemplar_phase.len(), height),
                ]);
                let mut s: Vec<(String, usize, usize)> = sizes
                    .into_iter()
                    .map(|(n, a, b)| (n.to_string(), a, b))
                    .collect();
                s.extend(per_level("followers", lens(&e.followers), FOLLOWERS, 1));
                s.extend(per_level("exemplars", lens(&e.exemplars), k, 0));
                s.extend(per_level(
                    "exemplar positions",
                    lens(&e.exemplar_phase),
                    1,
                    0,
                ));
                s
            }
        };
        sizes.extend(per_level("hit counts", lens(&self.hits), 1, 0));
        if let Some((name, found, want)) = sizes.iter().find(|(_, a, b)| a != b) {
            return bad(format!("{found} values of {name}, {want} expected"));
        }
        self.check_values(path)
    }

    /// The values of a model read from a file: what sizes a reproduction bounded, every
    /// statistic in its range, every index inside its map.
    fn check_values(&self, path: &Path) -> Result<(), PersistError> {
        let bad = |what: String| Err(corrupted(path, what));
        let p = self.config.params();
        let maps = &self.maps;
        // the events extension's part (empty for the paper's algorithm)
        let e = self.ev();
        let n0 = maps[0].len();
        let state = p.state_length;
        let demo_len = self.demo_len;
        // values that size the reproduction: no demonstration is longer than the longest, no
        // event longer than a demonstration
        let longest = demo_len[2];
        let lengths_ok = demo_len
            .iter()
            .all(|v| v.is_finite() && *v >= 0.0 && *v <= MAX_DEMO_SAMPLES)
            && demo_len[0] <= demo_len[1] + 1e-9
            && demo_len[1] <= demo_len[2] + 1e-9;
        if !lengths_ok {
            return bad(format!(
                "demonstration lengths {demo_len:?} (shortest, mean, longest) must be ordered and \
                 at most {MAX_DEMO_SAMPLES:e} samples"
            ));
        }
        let index_ok =
            |v: u32, n: usize| (v as usize) < n || v == u32::MAX || v == super::events::END;
        let stats_ok = self
            .demo_runs
            .iter()
            .chain(&self.dwell)
            .all(|v| v.is_finite() && *v >= 0.0 && *v <= longest)
            && self
                .accuracy
                .iter()
                .chain(&self.lookup)
                .chain(&e.heldout_accuracy)
                .chain(&e.heldout_lookup)
                .all(|v| v.is_finite() && (0.0..=1.0).contains(v))
            && e.threshold.iter().all(|v| v.is_finite() && *v >= 0.0)
            && e.follower_at
                .iter()
                .chain(e.exemplar_phase.iter().flatten())
                .all(|v| v.is_finite() && (0.0..=MAX_DEMO_SAMPLES).contains(v))
            && e.followers
                .iter()
                .zip(maps)
                .all(|(f, m)| f.iter().all(|&v| index_ok(v, m.len())))
            && e.exemplars.iter().enumerate().all(|(l, e)| {
                // level l's exemplars are entries of level l - 1 (none at the bottom)
                let below = if l == 0 { 0 } else { maps[l - 1].len() };
                e.iter().all(|&v| index_ok(v, below))
            });
        if !stats_ok {
            return bad("bad run statistics (a dwell or event count negative, non-finite or longer than the longest demonstration, an accuracy outside [0, 1], a position negative or non-finite, or a follower or exemplar outside its map)".into());
        }
        let finite = maps
            .iter()
            .all(|m| m.all_weights().iter().all(|v| v.is_finite()))
            && self
                .offset
                .iter()
                .chain(&self.qe)
                .chain(&self.te)
                .all(|v| v.is_finite())
            && self.scale.iter().all(|v| v.is_finite() && *v > 0.0);
        if !finite {
            return bad("non-finite weight or statistic (or a non-positive scale)".into());
        }
        let want = n0 * state;
        if let Some(knots) = &e.knots {
            if knots.len() != want {
                return bad(format!(
                    "{} posture values, the bottom level needs {want} (nodes x stateLength) or none",
                    knots.len()
                ));
            }
            if !knots.iter().all(|v| v.is_finite()) {
                return bad("a non-finite posture value".into());
            }
        }
        for (what, p) in [("start", &e.start_posture), ("end", &e.end_posture)] {
            if let Some(p) = p {
                if p.len() != state || !p.iter().all(|v| v.is_finite()) {
                    return bad(format!(
                        "{} {what}-posture values: none or stateLength = {state} finite values",
                        p.len()
                    ));
                }
            }
        }
        if e.demo_smoothness.as_ref().is_some_and(|d| {
            d.peak_step.len() != state
                || ![d.jerk, d.start_step]
                    .iter()
                    .chain(&d.peak_step)
                    .all(|v| v.is_finite() && *v >= 0.0)
        }) {
            return bad(format!(
                "the demonstrations' jerk, first step and stateLength = {state} largest steps: \
                 none or finite values >= 0"
            ));
        }
        if e.start_fade.is_some_and(|f| !(0.0..=1.0).contains(&f)) {
            return bad("the start's fade: none or a fraction in [0, 1]".into());
        }
        if let Some(s) = &e.start_knots {
            let sound = s.width.is_finite()
                && s.width > 0.0
                && s.starts.len() >= 3
                && s.starts.len() == s.knots.len()
                && s.starts.iter().all(|v| v.len() == state)
                && s.knots.iter().all(|v| v.len() == want)
                && s.starts
                    .iter()
                    .chain(&s.knots)
                    .flatten()
                    .all(|v| v.is_finite())
                && e.knots.is_some();
            if !sound {
                return bad(format!(
                    "start-weighted postures of {} demonstrations (width {}): at least 3 \
                     needed, each with stateLength finite start values and {want} posture \
                     values, a positive finite width, and the postures stored",
                    s.starts.len(),
                    s.width
                ));
            }
        }
        let traced = p.kind() == Algorithm::Events;
        match (&e.traces, traced) {
            (None, false) => Ok(()),
            (Some(t), true) => {
                let nodes: Vec<usize> = maps.iter().map(|m| m.len()).collect();
                t.check(p.memory, trace_places(p), &nodes)
                    .or_else(|why| bad(format!("traces: {why}")))
            }
            (_, traced) => bad(format!(
                "traces {} for a model of algorithm {}: stored exactly with algorithm = events",
                if traced { "missing" } else { "stored" },
                p.kind().name(),
            )),
        }
    }
}

#[cfg(test)]
mod tests;
