//! Save and load a trained hierarchy: a binary (`.bin`) and a plain-text (`.txt`) format,
//! both versioned and checksummed, written atomically. Every size read from a file is checked
//! against the embedded configuration and the bytes left before anything is allocated.

use std::path::{Path, PathBuf};

use crate::config::{parse_config, HsomConfig};
use crate::fsutil::write_atomic;
use crate::som::SelfOrganizingMap;

use super::algorithm::{input_dim, Hsom};
use super::errors::PersistError;
use super::events::{StartKnots, FOLLOWERS};

/// Magic bytes opening a binary model file.
pub(super) const MAGIC: &[u8; 8] = b"COSCOHSM";
/// First line of a plain-text model file.
pub(super) const TEXT_MAGIC: &str = "cosco-hsom model";
/// Format version of both formats. A model of several gestures has its own,
/// [`super::labels::GESTURES_FORMAT_VERSION`], always odd, so that no number means both: the
/// single-gesture format's are even from 10 on.
pub const FORMAT_VERSION: u32 = 20;

/// The longest demonstration a model file may record, samples (a day at 1 kHz): the
/// reproduction's length cap derives from it.
const MAX_DEMO_SAMPLES: f64 = 1e8;
/// Largest embedded configuration accepted (bytes).
const MAX_CONFIG: u64 = 1 << 20;

pub(super) fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// Sizes implied by a configuration: (rows, cols, dim) per level.
fn shapes(config: &HsomConfig) -> Vec<(usize, usize, usize)> {
    config
        .params()
        .levels
        .iter()
        .enumerate()
        .map(|(l, lp)| (lp.rows, lp.cols, input_dim(config, l)))
        .collect()
}

impl Hsom {
    /// Save to `path`: binary for `.bin`, plain text for `.txt` (atomic write). The bytes are
    /// read back with every check of [`Hsom::load`] first: a model that could not be loaded
    /// is refused here, and nothing is written.
    pub fn save(&self, path: &Path) -> Result<(), PersistError> {
        let bytes = match ext(path)? {
            Format::Bin => {
                let b = self.to_bytes();
                Hsom::from_bytes(&b, path)?;
                b
            }
            Format::Txt => {
                let t = self.to_text();
                Hsom::from_text(&t, path)?;
                t.into_bytes()
            }
        };
        write_atomic(path, &bytes).map_err(|source| PersistError::Io {
            path: path.to_path_buf(),
            source,
        })
    }

    /// Load a model saved by [`Hsom::save`]; the format is chosen by the extension.
    pub fn load(path: &Path) -> Result<Hsom, PersistError> {
        let fmt = ext(path)?;
        let bytes = std::fs::read(path).map_err(|source| PersistError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        match fmt {
            Format::Bin => Hsom::from_bytes(&bytes, path),
            Format::Txt => match std::str::from_utf8(&bytes) {
                Ok(t) => Hsom::from_text(t, path),
                Err(_) => Err(PersistError::BadMagic {
                    path: path.to_path_buf(),
                }),
            },
        }
    }

    /// The binary form: magic, version, configuration XML, weights and statistics (all
    /// little-endian), and an FNV-1a checksum of everything before it.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut b = Vec::new();
        b.extend_from_slice(MAGIC);
        b.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        let xml = self.config.to_xml();
        b.extend_from_slice(&(xml.len() as u64).to_le_bytes());
        b.extend_from_slice(xml.as_bytes());
        let f = |b: &mut Vec<u8>, v: f64| b.extend_from_slice(&v.to_le_bytes());
        b.extend_from_slice(&(self.maps.len() as u32).to_le_bytes());
        for (l, m) in self.maps.iter().enumerate() {
            for v in [m.rows(), m.cols(), m.dim()] {
                b.extend_from_slice(&(v as u32).to_le_bytes());
            }
            b.extend_from_slice(&self.trained[l].to_le_bytes());
            f(&mut b, self.qe[l]);
            f(&mut b, self.te[l]);
            for w in m.all_weights() {
                f(&mut b, w);
            }
            for &h in &self.hits[l] {
                b.extend_from_slice(&h.to_le_bytes());
            }
        }
        for &h in &self.end_hits {
            b.extend_from_slice(&h.to_le_bytes());
        }
        for &v in self.offset.iter().chain(&self.scale).chain(&self.demo_len) {
            f(&mut b, v);
        }
        for &v in self
            .demo_runs
            .iter()
            .chain(&self.dwell)
            .chain(&self.accuracy)
            .chain(&self.lookup)
            .chain(&self.threshold)
            .chain(&self.heldout_accuracy)
            .chain(&self.heldout_lookup)
            .chain(&self.follower_at)
        {
            f(&mut b, v);
        }
        for &v in self
            .followers
            .iter()
            .flatten()
            .chain(self.exemplars.iter().flatten())
        {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for &v in self.exemplar_phase.iter().flatten() {
            f(&mut b, v);
        }
        let knots = self.knots.as_deref().unwrap_or(&[]);
        b.extend_from_slice(&(knots.len() as u32).to_le_bytes());
        for &v in knots {
            f(&mut b, v);
        }
        let start = self.start_knots.as_ref();
        b.extend_from_slice(&(start.map_or(0, |k| k.starts.len()) as u32).to_le_bytes());
        if let Some(k) = start {
            f(&mut b, k.width);
            for &v in k.starts.iter().chain(&k.knots).flatten() {
                f(&mut b, v);
            }
        }
        let ends = self.end_postures.as_deref().unwrap_or(&[]);
        b.extend_from_slice(&(ends.len() as u32).to_le_bytes());
        for &v in ends {
            f(&mut b, v);
        }
        let traces = self.traces.as_ref().map_or_else(Vec::new, |t| t.to_words());
        b.extend_from_slice(&(traces.len() as u32).to_le_bytes());
        for v in traces {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for c in &self.columns {
            b.extend_from_slice(&(c.len() as u32).to_le_bytes());
            b.extend_from_slice(c.as_bytes());
        }
        let sum = fnv1a(&b);
        b.extend_from_slice(&sum.to_le_bytes());
        b
    }

    /// Read the binary form; `path` is only used in error messages.
    pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<Hsom, PersistError> {
        let mut r = Reader {
            b: bytes,
            pos: 0,
            path: path.to_path_buf(),
        };
        if bytes.len() < 8 || &bytes[..8] != MAGIC {
            return Err(PersistError::BadMagic {
                path: path.to_path_buf(),
            });
        }
        r.pos = 8;
        let version = r.u32("version")?;
        if version != FORMAT_VERSION {
            return Err(PersistError::Version {
                path: path.to_path_buf(),
                found: version,
                expected: FORMAT_VERSION,
            });
        }
        if bytes.len() < 8 + 4 + 8 {
            return Err(r.truncated("header"));
        }
        let body = &bytes[..bytes.len().saturating_sub(8)];
        let stored = u64::from_le_bytes(bytes[bytes.len() - 8..].try_into().unwrap_or([0; 8]));
        let xml_len = r.u64("configuration length")?;
        if xml_len > MAX_CONFIG || xml_len > r.remaining() as u64 {
            return Err(if xml_len > MAX_CONFIG {
                r.corrupted(format!("configuration length {xml_len} is implausible"))
            } else {
                r.truncated("configuration")
            });
        }
        let xml = r.take(xml_len as usize, "configuration")?;
        let xml = std::str::from_utf8(xml)
            .map_err(|_| r.corrupted("configuration is not UTF-8".into()))?;
        let config = parse_config(xml, &format!("{} (embedded configuration)", path.display()))
            .map_err(|e| r.corrupted(e.to_string()))?;
        let shapes = shapes(&config);
        let height = r.u32("height")? as usize;
        if height != shapes.len() {
            return Err(r.corrupted(format!(
                "{height} levels, the configuration has {}",
                shapes.len()
            )));
        }
        let mut maps = Vec::new();
        let (mut trained, mut qe, mut te, mut hits) = (vec![], vec![], vec![], vec![]);
        for (l, &(rows, cols, dim)) in shapes.iter().enumerate() {
            let got = (
                r.u32("rows")? as usize,
                r.u32("cols")? as usize,
                r.u32("dim")? as usize,
            );
            if got != (rows, cols, dim) {
                return Err(r.corrupted(format!(
                    "level {l} is {}x{} of dimension {}, the configuration says {rows}x{cols} of dimension {dim}",
                    got.0, got.1, got.2
                )));
            }
            trained.push(r.u64("trained")?);
            qe.push(r.f64("qe")?);
            te.push(r.f64("te")?);
            let n = rows * cols * dim;
            r.need(n * 8, "weights")?;
            let w: Vec<f64> = (0..n).map(|_| r.f64("weights")).collect::<Result<_, _>>()?;
            r.need(rows * cols * 4, "hits")?;
            hits.push(
                (0..rows * cols)
                    .map(|_| r.u32("hits"))
                    .collect::<Result<Vec<u32>, _>>()?,
            );
            maps.push(
                SelfOrganizingMap::from_weights(
                    rows,
                    cols,
                    dim,
                    config.params().levels[l].topology,
                    w,
                )
                .map_err(|e| r.corrupted(e.to_string()))?,
            );
        }
        let n0 = shapes[0].0 * shapes[0].1;
        r.need(n0 * 4, "end nodes")?;
        let end_hits = r.u32s(n0, "end nodes")?;
        let state = config.params().state_length;
        r.need((2 * state + 3) * 8, "normalisation")?;
        let offset = r.f64s(state, "offset")?;
        let scale = r.f64s(state, "scale")?;
        let dl = [r.f64("lengths")?, r.f64("lengths")?, r.f64("lengths")?];
        r.need((3 + n0 + 5 * height) * 8, "run statistics")?;
        let runs = [r.f64("runs")?, r.f64("runs")?, r.f64("runs")?];
        let dwell = r.f64s(n0, "dwell")?;
        let accuracy = r.f64s(height, "accuracy")?;
        let lookup = r.f64s(height, "lookup accuracy")?;
        let threshold = r.f64s(height, "match thresholds")?;
        let heldout_accuracy = r.f64s(height, "held-out accuracy")?;
        let heldout_lookup = r.f64s(height, "held-out lookup accuracy")?;
        let positions = (n0 + 1) * FOLLOWERS;
        r.need(positions * 8, "follower positions")?;
        let follower_at = r.f64s(positions, "follower positions")?;
        let mut followers = Vec::with_capacity(shapes.len());
        for &(rows, cols, _) in &shapes {
            let n = (rows * cols + 1) * FOLLOWERS;
            r.need(n * 4, "followers")?;
            followers.push(r.u32s(n, "followers")?);
        }
        let k = config.params().memory;
        let mut exemplars = Vec::with_capacity(shapes.len());
        for &(rows, cols, _) in &shapes {
            let n = rows * cols * k;
            r.need(n * 4, "exemplars")?;
            exemplars.push(r.u32s(n, "exemplars")?);
        }
        let mut exemplar_phase = Vec::with_capacity(shapes.len());
        for &(rows, cols, _) in &shapes {
            r.need(rows * cols * 8, "exemplar positions")?;
            exemplar_phase.push(r.f64s(rows * cols, "exemplar positions")?);
        }
        let nk = r.u32("postures length")? as usize;
        r.need(nk.saturating_mul(8), "postures")?;
        let knots = r.f64s(nk, "postures")?;
        let n0 = shapes[0].0 * shapes[0].1;
        let ns = r.u32("start-weighted demonstrations")? as usize;
        let start = if ns == 0 {
            None
        } else {
            let per = state.saturating_mul(n0 + 1).saturating_mul(8);
            r.need(
                ns.saturating_mul(per).saturating_add(8),
                "start-weighted postures",
            )?;
            let width = r.f64s(1, "start width")?[0];
            let mut starts = Vec::with_capacity(ns);
            for _ in 0..ns {
                starts.push(r.f64s(state, "starts")?);
            }
            let mut placed = Vec::with_capacity(ns);
            for _ in 0..ns {
                placed.push(r.f64s(n0 * state, "start-weighted postures")?);
            }
            Some(StartKnots {
                starts,
                knots: placed,
                width,
            })
        };
        let ne = r.u32("end postures length")? as usize;
        r.need(ne.saturating_mul(8), "end postures")?;
        let ends = r.f64s(ne, "end postures")?;
        let nt = r.u32("traces length")? as usize;
        r.need(nt.saturating_mul(4), "traces")?;
        let traces = r.u32s(nt, "traces")?;
        let mut columns = Vec::with_capacity(state.min(r.remaining() / 4));
        for _ in 0..state {
            let n = r.u32("column name length")? as usize;
            r.need(n, "column name")?;
            let name = r.take(n, "column name")?;
            columns.push(
                std::str::from_utf8(name)
                    .map_err(|_| r.corrupted("column name is not UTF-8".into()))?
                    .to_string(),
            );
        }
        if r.remaining() != 8 {
            return Err(r.corrupted(format!(
                "{} unexpected bytes at the end",
                r.remaining() as i64 - 8
            )));
        }
        if fnv1a(body) != stored {
            return Err(r.corrupted("checksum mismatch".into()));
        }
        build(
            config,
            maps,
            offset,
            scale,
            trained,
            hits,
            end_hits,
            qe,
            te,
            dl,
            Extra {
                runs,
                dwell,
                columns,
                accuracy,
                lookup,
                threshold,
                heldout_accuracy,
                heldout_lookup,
                follower_at,
                exemplar_phase,
                followers,
                exemplars,
                knots,
                start,
                ends,
                traces,
            },
            path,
        )
    }

    /// The plain-text form: a format line, the version, the configuration XML, then one line
    /// per node and statistic, and a checksum line.
    pub fn to_text(&self) -> String {
        use std::fmt::Write;
        let mut s = String::new();
        let xml = self.config.to_xml();
        let _ = writeln!(s, "{TEXT_MAGIC}");
        let _ = writeln!(s, "version {FORMAT_VERSION}");
        let _ = writeln!(s, "config {}", xml.lines().count());
        for line in xml.lines() {
            let _ = writeln!(s, "{line}");
        }
        fn line<T: ToString>(s: &mut String, key: &str, values: &[T]) {
            let v: Vec<String> = values.iter().map(T::to_string).collect();
            let _ = writeln!(s, "{key} {}", v.join(" "));
        }
        line(&mut s, "offset", &self.offset);
        line(&mut s, "scale", &self.scale);
        line(&mut s, "demo-lengths", &self.demo_len);
        line(&mut s, "end-nodes", &self.end_hits);
        line(&mut s, "demo-runs", &self.demo_runs);
        line(&mut s, "dwell", &self.dwell);
        line(&mut s, "accuracy", &self.accuracy);
        line(&mut s, "lookup-accuracy", &self.lookup);
        line(&mut s, "match-thresholds", &self.threshold);
        line(&mut s, "heldout-accuracy", &self.heldout_accuracy);
        line(&mut s, "heldout-lookup-accuracy", &self.heldout_lookup);
        line(&mut s, "follower-positions", &self.follower_at);
        for (l, f) in self.followers.iter().enumerate() {
            line(&mut s, &format!("followers-{l}"), f);
        }
        for (l, e) in self.exemplars.iter().enumerate() {
            line(&mut s, &format!("exemplars-{l}"), e);
        }
        for (l, e) in self.exemplar_phase.iter().enumerate() {
            line(&mut s, &format!("exemplar-positions-{l}"), e);
        }
        let knots: Vec<String> = self
            .knots
            .iter()
            .flatten()
            .map(|v| format!(" {v}"))
            .collect();
        let _ = writeln!(s, "postures{}", knots.concat());
        let start = self.start_knots.as_ref();
        let _ = writeln!(
            s,
            "start-demonstrations {}",
            start.map_or(0, |k| k.starts.len())
        );
        if let Some(k) = start {
            let _ = writeln!(s, "start-width {}", k.width);
            for (i, v) in k.starts.iter().enumerate() {
                line(&mut s, &format!("start-{i}"), v);
            }
            for (i, v) in k.knots.iter().enumerate() {
                line(&mut s, &format!("start-postures-{i}"), v);
            }
        }
        let ends: Vec<String> = self
            .end_postures
            .iter()
            .flatten()
            .map(|v| format!(" {v}"))
            .collect();
        let _ = writeln!(s, "end-postures{}", ends.concat());
        let traces: Vec<String> = self
            .traces
            .iter()
            .flat_map(|t| t.to_words())
            .map(|v| format!(" {v}"))
            .collect();
        let _ = writeln!(s, "traces{}", traces.concat());
        let _ = writeln!(s, "columns {}", self.columns.len());
        for c in &self.columns {
            let _ = writeln!(s, "column {}", c.replace(['\n', '\r'], " "));
        }
        for (l, m) in self.maps.iter().enumerate() {
            let _ = writeln!(
                s,
                "level {l} rows {} cols {} dim {} trained {} qe {} te {}",
                m.rows(),
                m.cols(),
                m.dim(),
                self.trained[l],
                self.qe[l],
                self.te[l]
            );
            line(&mut s, "hits", &self.hits[l]);
            for i in 0..m.len() {
                line(&mut s, "node", &m.weights(i));
            }
        }
        let sum = fnv1a(s.as_bytes());
        let _ = writeln!(s, "checksum {sum:016x}");
        s
    }

    /// Read the plain-text form; `path` is only used in error messages.
    pub fn from_text(text: &str, path: &Path) -> Result<Hsom, PersistError> {
        let p = path.to_path_buf();
        let corrupted = |what: String| PersistError::Corrupted {
            path: p.clone(),
            what,
        };
        let truncated = |what: &str| PersistError::Truncated {
            path: p.clone(),
            what: what.to_string(),
        };
        let mut lines = text.lines().enumerate();
        match lines.next() {
            Some((_, l)) if l.trim_end() == TEXT_MAGIC => {}
            _ => return Err(PersistError::BadMagic { path: p.clone() }),
        }
        let version = match lines.next() {
            None => return Err(truncated("version line")),
            Some((_, l)) => l
                .strip_prefix("version ")
                .and_then(|v| v.trim().parse::<u32>().ok())
                .ok_or_else(|| corrupted(format!("bad version line {l:?}")))?,
        };
        if version != FORMAT_VERSION {
            return Err(PersistError::Version {
                path: p.clone(),
                found: version,
                expected: FORMAT_VERSION,
            });
        }
        // checksum over everything before the last line
        let body_end = text
            .trim_end_matches('\n')
            .rfind('\n')
            .map(|i| i + 1)
            .unwrap_or(0);
        let last = text[body_end..].trim();
        let stored = last
            .strip_prefix("checksum ")
            .and_then(|h| u64::from_str_radix(h.trim(), 16).ok())
            .ok_or_else(|| truncated("checksum line missing"))?;
        let total_lines = text.lines().count();
        let mut next = |what: &str| lines.next().map(|(_, l)| l).ok_or_else(|| truncated(what));
        let cl = next("config line")?;
        let n: usize = cl
            .strip_prefix("config ")
            .and_then(|v| v.trim().parse().ok())
            .ok_or_else(|| corrupted(format!("bad config line {cl:?}")))?;
        if n > total_lines {
            return Err(truncated("configuration"));
        }
        let mut xml = String::new();
        for _ in 0..n {
            xml.push_str(next("configuration")?);
            xml.push('\n');
        }
        let config = parse_config(
            &xml,
            &format!("{} (embedded configuration)", path.display()),
        )
        .map_err(|e| corrupted(e.to_string()))?;
        let shapes = shapes(&config);
        let state = config.params().state_length;
        fn values<T: std::str::FromStr>(
            line: &str,
            key: &str,
            count: usize,
            corrupted: &dyn Fn(String) -> PersistError,
        ) -> Result<Vec<T>, PersistError> {
            let rest = line.strip_prefix(key).ok_or_else(|| {
                corrupted(format!("expected a {key:?} line, found {:.40?}", line))
            })?;
            let v: Vec<T> = rest
                .split_whitespace()
                .take(count + 1)
                .map(|t| {
                    t.parse::<T>()
                        .map_err(|_| corrupted(format!("bad number {t:?} in {key:?} line")))
                })
                .collect::<Result<_, _>>()?;
            if v.len() != count {
                return Err(corrupted(format!(
                    "{key:?} line has {} values, expected {count}",
                    v.len()
                )));
            }
            Ok(v)
        }
        let offset: Vec<f64> = values(next("offset")?, "offset ", state, &corrupted)?;
        let scale: Vec<f64> = values(next("scale")?, "scale ", state, &corrupted)?;
        let dl: Vec<f64> = values(next("demo-lengths")?, "demo-lengths ", 3, &corrupted)?;
        let n0 = shapes[0].0 * shapes[0].1;
        let end_hits: Vec<u32> = values(next("end-nodes")?, "end-nodes ", n0, &corrupted)?;
        let runs: Vec<f64> = values(next("demo-runs")?, "demo-runs ", 3, &corrupted)?;
        let dwell: Vec<f64> = values(next("dwell")?, "dwell ", n0, &corrupted)?;
        let accuracy: Vec<f64> = values(next("accuracy")?, "accuracy ", shapes.len(), &corrupted)?;
        let lookup: Vec<f64> = values(
            next("lookup-accuracy")?,
            "lookup-accuracy ",
            shapes.len(),
            &corrupted,
        )?;
        let threshold: Vec<f64> = values(
            next("match-thresholds")?,
            "match-thresholds ",
            shapes.len(),
            &corrupted,
        )?;
        let heldout_accuracy: Vec<f64> = values(
            next("heldout-accuracy")?,
            "heldout-accuracy ",
            shapes.len(),
            &corrupted,
        )?;
        let heldout_lookup: Vec<f64> = values(
            next("heldout-lookup-accuracy")?,
            "heldout-lookup-accuracy ",
            shapes.len(),
            &corrupted,
        )?;
        let follower_at: Vec<f64> = values(
            next("follower-positions")?,
            "follower-positions ",
            (n0 + 1) * FOLLOWERS,
            &corrupted,
        )?;
        let mut followers = Vec::with_capacity(shapes.len());
        for (l, &(rows, cols, _)) in shapes.iter().enumerate() {
            let key = format!("followers-{l}");
            let f: Vec<u32> = values(
                next(&key)?,
                &format!("{key} "),
                (rows * cols + 1) * FOLLOWERS,
                &corrupted,
            )?;
            followers.push(f);
        }
        let k = config.params().memory;
        let mut exemplars = Vec::with_capacity(shapes.len());
        for (l, &(rows, cols, _)) in shapes.iter().enumerate() {
            let key = format!("exemplars-{l}");
            let e: Vec<u32> = values(next(&key)?, &format!("{key} "), rows * cols * k, &corrupted)?;
            exemplars.push(e);
        }
        let mut exemplar_phase = Vec::with_capacity(shapes.len());
        for (l, &(rows, cols, _)) in shapes.iter().enumerate() {
            let key = format!("exemplar-positions-{l}");
            let e: Vec<f64> = values(next(&key)?, &format!("{key} "), rows * cols, &corrupted)?;
            exemplar_phase.push(e);
        }
        let pl = next("postures")?;
        let knots: Vec<f64> = pl
            .strip_prefix("postures")
            .ok_or_else(|| corrupted(format!("expected a \"postures\" line, found {pl:.40?}")))?
            .split_whitespace()
            // one more than the bottom level can hold: a longer line is refused, not parsed
            .take(n0 * state + 1)
            .map(|t| {
                t.parse::<f64>()
                    .map_err(|_| corrupted(format!("bad number {t:?} in \"postures\" line")))
            })
            .collect::<Result<_, _>>()?;
        let ns: Vec<usize> = values(
            next("start-demonstrations")?,
            "start-demonstrations ",
            1,
            &corrupted,
        )?;
        let start = if ns[0] == 0 {
            None
        } else {
            let width: Vec<f64> = values(next("start-width")?, "start-width ", 1, &corrupted)?;
            let mut starts = Vec::new();
            for i in 0..ns[0] {
                let key = format!("start-{i}");
                starts.push(values(next(&key)?, &format!("{key} "), state, &corrupted)?);
            }
            let mut placed = Vec::new();
            for i in 0..ns[0] {
                let key = format!("start-postures-{i}");
                placed.push(values(
                    next(&key)?,
                    &format!("{key} "),
                    n0 * state,
                    &corrupted,
                )?);
            }
            Some(StartKnots {
                starts,
                knots: placed,
                width: width[0],
            })
        };
        let el = next("end-postures")?;
        let ends: Vec<f64> = el
            .strip_prefix("end-postures")
            .ok_or_else(|| {
                corrupted(format!(
                    "expected an \"end-postures\" line, found {el:.40?}"
                ))
            })?
            .split_whitespace()
            // one more than the bottom level can hold: a longer line is refused, not parsed
            .take(n0 + state + 1)
            .map(|t| {
                t.parse::<f64>()
                    .map_err(|_| corrupted(format!("bad number {t:?} in \"end-postures\" line")))
            })
            .collect::<Result<_, _>>()?;
        let tl = next("traces")?;
        let traces: Vec<u32> = tl
            .strip_prefix("traces")
            .ok_or_else(|| corrupted(format!("expected a \"traces\" line, found {tl:.40?}")))?
            .split_whitespace()
            .map(|t| {
                t.parse::<u32>()
                    .map_err(|_| corrupted(format!("bad number {t:?} in \"traces\" line")))
            })
            .collect::<Result<_, _>>()?;
        let nc: Vec<usize> = values(next("columns")?, "columns ", 1, &corrupted)?;
        if nc[0] != state {
            return Err(corrupted(format!(
                "{} column names, the configuration has stateLength {state}",
                nc[0]
            )));
        }
        let mut columns = Vec::with_capacity(state);
        for _ in 0..state {
            let l = next("column")?;
            let name = l
                .strip_prefix("column ")
                .or_else(|| (l == "column").then_some(""))
                .ok_or_else(|| corrupted(format!("expected a column line, found {l:.40?}")))?;
            columns.push(name.to_string());
        }
        let mut maps = Vec::new();
        let (mut trained, mut qe, mut te, mut hits) = (vec![], vec![], vec![], vec![]);
        for (l, &(rows, cols, dim)) in shapes.iter().enumerate() {
            let head = next("level line")?;
            let t: Vec<&str> = head.split_whitespace().collect();
            let expect = [
                "level".to_string(),
                l.to_string(),
                "rows".into(),
                rows.to_string(),
                "cols".into(),
                cols.to_string(),
                "dim".into(),
                dim.to_string(),
                "trained".into(),
            ];
            if t.len() != 14
                || t[..9].iter().zip(&expect).any(|(a, b)| a != b)
                || t[10] != "qe"
                || t[12] != "te"
            {
                return Err(corrupted(format!(
                    "level {l}: expected \"level {l} rows {rows} cols {cols} dim {dim} trained N qe Q te T\", found {head:.80?}"
                )));
            }
            trained.push(
                t[9].parse()
                    .map_err(|_| corrupted(format!("bad trained count {:?}", t[9])))?,
            );
            qe.push(
                t[11]
                    .parse()
                    .map_err(|_| corrupted(format!("bad qe {:?}", t[11])))?,
            );
            te.push(
                t[13]
                    .parse()
                    .map_err(|_| corrupted(format!("bad te {:?}", t[13])))?,
            );
            hits.push(values::<u32>(
                next("hits")?,
                "hits ",
                rows * cols,
                &corrupted,
            )?);
            if rows * cols > total_lines {
                return Err(truncated("nodes"));
            }
            let mut w = Vec::with_capacity(rows * cols * dim);
            for _ in 0..rows * cols {
                w.extend(values::<f64>(next("node")?, "node ", dim, &corrupted)?);
            }
            maps.push(
                SelfOrganizingMap::from_weights(
                    rows,
                    cols,
                    dim,
                    config.params().levels[l].topology,
                    w,
                )
                .map_err(|e| corrupted(e.to_string()))?,
            );
        }
        match next("checksum") {
            Ok(l) if l.starts_with("checksum ") => {}
            Ok(l) => return Err(corrupted(format!("unexpected line {l:.40?}"))),
            Err(e) => return Err(e),
        }
        if fnv1a(&text.as_bytes()[..body_end]) != stored {
            return Err(corrupted("checksum mismatch".into()));
        }
        build(
            config,
            maps,
            offset,
            scale,
            trained,
            hits,
            end_hits,
            qe,
            te,
            [dl[0], dl[1], dl[2]],
            Extra {
                runs: [runs[0], runs[1], runs[2]],
                dwell,
                columns,
                accuracy,
                lookup,
                threshold,
                heldout_accuracy,
                heldout_lookup,
                follower_at,
                exemplar_phase,
                followers,
                exemplars,
                knots,
                start,
                ends,
                traces,
            },
            path,
        )
    }
}

#[allow(clippy::too_many_arguments)]
fn build(
    config: HsomConfig,
    maps: Vec<SelfOrganizingMap>,
    offset: Vec<f64>,
    scale: Vec<f64>,
    trained: Vec<u64>,
    hits: Vec<Vec<u32>>,
    end_hits: Vec<u32>,
    qe: Vec<f64>,
    te: Vec<f64>,
    demo_len: [f64; 3],
    extra: Extra,
    path: &Path,
) -> Result<Hsom, PersistError> {
    let n0 = maps.first().map_or(0, |m| m.len()) as u32;
    // values that size the reproduction: no demonstration is longer than the longest, no
    // event longer than a demonstration
    let longest = demo_len[2];
    let lengths_ok = demo_len
        .iter()
        .all(|v| v.is_finite() && *v >= 0.0 && *v <= MAX_DEMO_SAMPLES)
        && demo_len[0] <= demo_len[1] + 1e-9
        && demo_len[1] <= demo_len[2] + 1e-9;
    if !lengths_ok {
        return Err(PersistError::Corrupted {
            path: path.to_path_buf(),
            what: format!(
                "demonstration lengths {demo_len:?} (shortest, mean, longest) must be ordered and \
                 at most {MAX_DEMO_SAMPLES:e} samples"
            ),
        });
    }
    let stats_ok = extra
        .runs
        .iter()
        .all(|v| v.is_finite() && *v >= 0.0 && *v <= longest)
        && extra
            .dwell
            .iter()
            .all(|v| v.is_finite() && *v >= 0.0 && *v <= longest)
        && extra
            .accuracy
            .iter()
            .chain(&extra.lookup)
            .chain(&extra.heldout_accuracy)
            .chain(&extra.heldout_lookup)
            .all(|v| v.is_finite() && (0.0..=1.0).contains(v))
        && extra.threshold.iter().all(|v| v.is_finite() && *v >= 0.0)
        && extra
            .follower_at
            .iter()
            .chain(extra.exemplar_phase.iter().flatten())
            .all(|v| v.is_finite() && (0.0..=MAX_DEMO_SAMPLES).contains(v))
        && extra.followers.iter().zip(&maps).all(|(f, m)| {
            f.iter()
                .all(|&v| (v as usize) < m.len() || v == u32::MAX || v == super::events::END)
        })
        && extra.exemplars.len() == maps.len()
        && extra.exemplars.iter().enumerate().all(|(l, e)| {
            // level l's exemplars are entries of level l - 1 (none at the bottom)
            let below = if l == 0 { 0 } else { maps[l - 1].len() };
            e.iter()
                .all(|&v| (v as usize) < below || v == u32::MAX || v == super::events::END)
        });
    if !stats_ok {
        return Err(PersistError::Corrupted {
            path: path.to_path_buf(),
            what: "bad run statistics (a dwell or event count negative, non-finite or longer than the longest demonstration, an accuracy outside [0, 1], a position negative or non-finite, or a follower or exemplar outside its map)".into(),
        });
    }
    let finite = maps
        .iter()
        .all(|m| m.all_weights().iter().all(|v| v.is_finite()))
        && offset
            .iter()
            .chain(&qe)
            .chain(&te)
            .chain(&demo_len)
            .all(|v| v.is_finite())
        && scale.iter().all(|v| v.is_finite() && *v > 0.0);
    if !finite {
        return Err(PersistError::Corrupted {
            path: path.to_path_buf(),
            what: "non-finite weight or statistic (or a non-positive scale)".into(),
        });
    }
    let want = n0 as usize * config.params().state_length;
    if !(extra.knots.is_empty() || extra.knots.len() == want) {
        return Err(PersistError::Corrupted {
            path: path.to_path_buf(),
            what: format!(
                "{} posture values, the bottom level needs {want} (nodes x stateLength) or none",
                extra.knots.len()
            ),
        });
    }
    if !extra.knots.iter().all(|v| v.is_finite()) {
        return Err(PersistError::Corrupted {
            path: path.to_path_buf(),
            what: "a non-finite posture value".into(),
        });
    }
    let state = config.params().state_length;
    let want_ends = n0 as usize + state;
    let ends_sound = (extra.ends.is_empty() || extra.ends.len() == want_ends)
        && extra.ends.iter().all(|v| v.is_finite())
        && extra.ends[..extra.ends.len().min(n0 as usize)]
            .iter()
            .all(|&c| c >= 0.0 && c.fract() == 0.0 && c <= MAX_DEMO_SAMPLES);
    if !ends_sound {
        return Err(PersistError::Corrupted {
            path: path.to_path_buf(),
            what: format!(
                "{} end-posture values: none or {want_ends} (a count of demonstrations per \
                 node, each a whole number >= 0, then stateLength finite values)",
                extra.ends.len()
            ),
        });
    }
    if let Some(StartKnots {
        starts,
        knots: placed,
        width,
    }) = &extra.start
    {
        let state = config.params().state_length;
        let sound = width.is_finite()
            && *width > 0.0
            && starts.len() >= 3
            && starts.len() == placed.len()
            && starts.iter().all(|v| v.len() == state)
            && placed.iter().all(|v| v.len() == want)
            && starts.iter().chain(placed).flatten().all(|v| v.is_finite())
            && !extra.knots.is_empty();
        if !sound {
            return Err(PersistError::Corrupted {
                path: path.to_path_buf(),
                what: format!(
                    "start-weighted postures of {} demonstrations (width {width}): at least 3 \
                     needed, each with stateLength finite start values and {want} posture \
                     values, a positive finite width, and the postures stored",
                    starts.len()
                ),
            });
        }
    }
    let p = config.params();
    let traced = p.kind() == crate::config::Algorithm::Events;
    if traced == extra.traces.is_empty() {
        return Err(PersistError::Corrupted {
            path: path.to_path_buf(),
            what: format!(
                "traces {} for a model of algorithm {}: stored exactly with algorithm = events",
                if traced { "missing" } else { "stored" },
                p.kind().name(),
            ),
        });
    }
    let traces = if extra.traces.is_empty() {
        None
    } else {
        let nodes: Vec<usize> = maps.iter().map(|m| m.len()).collect();
        let k = config.params().memory;
        Some(
            super::events::Traces::from_words(
                &extra.traces,
                k,
                super::events::trace_places(config.params()),
                &nodes,
            )
            .map_err(|why| PersistError::Corrupted {
                path: path.to_path_buf(),
                what: format!("traces: {why}"),
            })?,
        )
    };
    Ok(Hsom {
        config,
        maps,
        offset,
        scale,
        trained,
        hits,
        end_hits,
        qe,
        te,
        demo_len,
        demo_runs: extra.runs,
        dwell: extra.dwell,
        columns: extra.columns,
        heldout_accuracy: extra.heldout_accuracy,
        heldout_lookup: extra.heldout_lookup,
        follower_at: extra.follower_at,
        exemplar_phase: extra.exemplar_phase,
        accuracy: extra.accuracy,
        lookup: extra.lookup,
        threshold: extra.threshold,
        followers: extra.followers,
        exemplars: extra.exemplars,
        knots: (!extra.knots.is_empty()).then_some(extra.knots),
        start_knots: extra.start,
        traces,
        end_postures: (!extra.ends.is_empty()).then_some(extra.ends),
    })
}

/// The version-2 additions: run statistics and column names.
struct Extra {
    /// Per bottom node the posture a reproduction places its events at (empty: the
    /// weights); `stateLength` values per node.
    knots: Vec<f64>,
    /// With `consensus = start`, where the starts are used: the width, each training
    /// demonstration's first posture and its placement of every bottom node.
    start: Option<StartKnots>,
    /// Per bottom node, the number of demonstrations whose last event was on it, then the
    /// mean of all their last postures (empty: none stored).
    ends: Vec<f64>,
    runs: [f64; 3],
    dwell: Vec<f64>,
    columns: Vec<String>,
    accuracy: Vec<f64>,
    lookup: Vec<f64>,
    threshold: Vec<f64>,
    heldout_accuracy: Vec<f64>,
    heldout_lookup: Vec<f64>,
    follower_at: Vec<f64>,
    exemplar_phase: Vec<Vec<f64>>,
    followers: Vec<Vec<u32>>,
    exemplars: Vec<Vec<u32>>,
    /// [`super::events::Traces::to_words`] (empty: none stored).
    traces: Vec<u32>,
}

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

struct Reader<'a> {
    b: &'a [u8],
    pos: usize,
    path: PathBuf,
}

impl<'a> Reader<'a> {
    fn remaining(&self) -> usize {
        self.b.len() - self.pos
    }
    fn truncated(&self, what: &str) -> PersistError {
        PersistError::Truncated {
            path: self.path.clone(),
            what: what.to_string(),
        }
    }
    fn corrupted(&self, what: String) -> PersistError {
        PersistError::Corrupted {
            path: self.path.clone(),
            what,
        }
    }
    /// Fail unless `n` bytes remain before the checksum.
    fn need(&self, n: usize, what: &str) -> Result<(), PersistError> {
        if self.remaining() < n.saturating_add(8) {
            Err(self.truncated(what))
        } else {
            Ok(())
        }
    }
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], PersistError> {
        if self.remaining() < n {
            return Err(self.truncated(what));
        }
        let b: &'a [u8] = self.b;
        let s = &b[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }
    fn u32(&mut self, what: &str) -> Result<u32, PersistError> {
        let s = self.take(4, what)?;
        Ok(u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
    }
    fn u64(&mut self, what: &str) -> Result<u64, PersistError> {
        let s = self.take(8, what)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(s);
        Ok(u64::from_le_bytes(a))
    }
    fn f64(&mut self, what: &str) -> Result<f64, PersistError> {
        Ok(f64::from_bits(self.u64(what)?))
    }
    /// `n` f64 values; the caller has checked with [`Reader::need`] that they are there.
    fn f64s(&mut self, n: usize, what: &str) -> Result<Vec<f64>, PersistError> {
        (0..n).map(|_| self.f64(what)).collect()
    }
    /// `n` u32 values; the caller has checked with [`Reader::need`] that they are there.
    fn u32s(&mut self, n: usize, what: &str) -> Result<Vec<u32>, PersistError> {
        (0..n).map(|_| self.u32(what)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Saving runs the loader's checks first: a model whose statistics a file could not hold
    /// is refused and no file appears.
    #[test]
    fn saving_refuses_what_loading_would_refuse_and_writes_nothing() {
        let mut p = crate::config::HsomParams::table1();
        p.state_length = 1;
        p.action_length = 1;
        let series: Vec<Vec<Vec<f64>>> = (0..2)
            .map(|k| (0..30 + k).map(|i| vec![(i as f64 / 10.0).sin()]).collect())
            .collect();
        let mut m = p.check("t").unwrap().fit_series(&series).unwrap();
        let dir = tempfile::tempdir().unwrap();
        for name in ["m.bin", "m.txt"] {
            m.save(&dir.path().join(name)).unwrap();
        }
        m.dwell[0] = 1e300;
        for name in ["bad.bin", "bad.txt"] {
            let path = dir.path().join(name);
            let e = m.save(&path).unwrap_err();
            assert!(matches!(e, PersistError::Corrupted { .. }), "{e}");
            assert!(!path.exists(), "{name} was written");
        }
    }
}
