//! Stored references: a work–precision reference costs minutes (tens of them for a sudden load),
//! and depends only on the scene, so it is computed once and kept beside the scene, under
//! `references/<scene name>.yaml` (how it was made and how settled it is, the headlines) and
//! `references/<scene name>.history.csv` (the history it is compared on, on the output grid).
//!
//! A stored reference is used only for the scene text it was made from: the file carries the
//! FNV-1a hash of the scene file, and any edit of the scene makes it stale. A change of the code
//! that moves the physics is caught by the test that reruns every stored reference at a coarser
//! tolerance (`studies/tradeoff.rs`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{reference, reference_method, Headline, MeansReference, Plan, Reference};
use crate::error::Error;
use crate::files::{content_hash, read_text};
use crate::ode::Method;
use crate::output::{io_error, write, yaml};
use crate::say;
use crate::scene::Scene;

/// The hash of the scene file at `path`.
pub fn scene_hash(path: &Path) -> Result<String, Error> {
    let text = crate::files::read_text(path, crate::scene::MAX_SCENE_BYTES, "scene file")?;
    Ok(content_hash(&text))
}

/// Where the reference of the scene named `name`, read from `scene_file`, is kept.
pub fn stored_path(scene_file: &Path, name: &str) -> PathBuf {
    scene_file
        .parent()
        .unwrap_or(Path::new("."))
        .join("references")
        .join(format!("{name}.yaml"))
}

/// Largest stored reference file read: headlines and windowed means, a few kilobytes.
const MAX_STORED_BYTES: u64 = 4 << 20;
/// Largest stored history read: a reference on a fine output grid is a few megabytes.
const MAX_HISTORY_BYTES: u64 = 256 << 20;

#[derive(Serialize, Deserialize)]
struct StoredFile {
    scene: String,
    scene_hash: String,
    made_by: String,
    method: String,
    rtol: f64,
    elements: Option<usize>,
    /// Absent where the reference kept the scene's degree.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    order: Option<usize>,
    settled_to: f64,
    /// Absent in a reference stored before the mesh was checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    mesh_gap: Option<f64>,
    wall_s: f64,
    headlines: Vec<Headline>,
    history_columns: usize,
    /// The content hash of the history file beside it: a history cut or edited is not the
    /// reference, and would score every run against itself.
    #[serde(default)]
    history_hash: Option<String>,
    /// The windowed means' own reference, where one was made (`tradeoff --reference-means`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    means: Option<StoredMeans>,
}

#[derive(Serialize, Deserialize)]
struct StoredMeans {
    made_by: String,
    method: String,
    rtol: f64,
    elements: Option<usize>,
    /// Absent where the means' reference kept the scene's degree.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    order: Option<usize>,
    resolves: f64,
    scale: f64,
    wall_s: f64,
    values: Vec<f64>,
}

impl StoredMeans {
    fn from(m: &MeansReference) -> Self {
        StoredMeans {
            made_by: m.made_by.clone(),
            method: m.method.name().to_string(),
            rtol: m.rtol,
            elements: m.elements,
            order: m.order,
            resolves: m.resolves,
            scale: m.scale,
            wall_s: m.wall_s,
            values: m.values.clone(),
        }
    }

    fn read(self) -> Result<MeansReference, String> {
        let method = Method::from_name(&self.method)
            .ok_or_else(|| format!("its windowed means name an unknown method, {}", self.method))?;
        let finite = [self.rtol, self.resolves, self.scale, self.wall_s]
            .iter()
            .chain(&self.values)
            .all(|x| x.is_finite());
        if !finite || self.scale <= 0.0 || self.resolves < 0.0 {
            return Err(
                "its windowed means hold a number that is not finite or out of range".into(),
            );
        }
        Ok(MeansReference {
            method,
            rtol: self.rtol,
            elements: self.elements,
            order: self.order,
            values: self.values,
            scale: self.scale,
            resolves: self.resolves,
            wall_s: self.wall_s,
            made_by: self.made_by,
        })
    }
}

/// Write `reference` for the scene `name` (file hash `hash`) to `path` and its history beside it.
pub fn store(reference: &Reference, name: &str, hash: &str, path: &Path) -> Result<(), Error> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| io_error(dir, e))?;
    let mut csv = String::new();
    for (t, values) in &reference.history {
        let _ = write!(csv, "{t:e}");
        for v in values {
            let _ = write!(csv, ",{v:e}");
        }
        csv.push('\n');
    }
    let file = StoredFile {
        scene: name.to_string(),
        scene_hash: hash.to_string(),
        made_by: reference.made_by.clone(),
        method: reference.method.name().to_string(),
        rtol: reference.rtol,
        elements: reference.elements,
        order: reference.order,
        settled_to: reference.settled_to,
        mesh_gap: reference.mesh_gap,
        wall_s: reference.wall_s,
        headlines: reference.headlines.clone(),
        history_hash: Some(content_hash(&csv)),
        history_columns: reference.history.first().map_or(0, |(_, v)| v.len()),
        means: reference.means.as_ref().map(StoredMeans::from),
    };
    write(&history_path(path), &csv)?;
    write(path, &yaml(&file)?)
}

fn history_path(path: &Path) -> PathBuf {
    path.with_extension("history.csv")
}

/// The reference for `scene`, read from `file`: the stored one where it serves, otherwise
/// computed, and computed and stored when `recompute` is set (`--reference`). The line says
/// which, and why.
pub fn reference_for(
    scene: &Scene,
    file: &Path,
    plan: &Plan,
    recompute: bool,
    made_by: &str,
) -> Result<(Reference, String), Error> {
    let path = stored_path(file, &scene.name);
    let hash = scene_hash(file)?;
    let why = if recompute {
        "asked to compute it again".to_string()
    } else {
        let scene_order = scene.beam().map(|b| b.beam.order);
        match load(&path, &hash, plan, reference_method(scene), scene_order) {
            Stored::Usable(r) => {
                let line = format!("stored reference {} ({hash})", path.display());
                return Ok((*r, line));
            }
            Stored::Missing => {
                format!("no stored reference at {}", path.display())
            }
            Stored::Stale(why) => {
                format!("the stored reference does not serve: {why}")
            }
        }
    };
    say!("{}: computing the reference ({why})…", scene.name);
    let mut r = reference(scene, plan, made_by)?;
    let line = if recompute {
        r.means = stored_means(&path, &hash);
        store(&r, &scene.name, &hash, &path)?;
        format!("computed and stored the reference in {}", path.display())
    } else {
        format!("computed the reference ({why}; `{made_by}` stores one)")
    };
    Ok((r, line))
}

/// Why a stored reference cannot serve, or the reference itself.
pub enum Stored {
    Usable(Box<Reference>),
    Missing,
    Stale(String),
}

/// The reference stored at `path`, if it was made from the scene text hashed `hash` and is at
/// least as fine as `plan` asks (a mesh twice its finest at its highest degree, an rtol at or
/// below the one its reference starts at, `Plan::reference_rtol`). `scene_order` is the
/// degree of the scene's own elements.
pub fn load(
    path: &Path,
    hash: &str,
    plan: &Plan,
    method: Method,
    scene_order: Option<usize>,
) -> Stored {
    if !path.exists() {
        return Stored::Missing;
    }
    match read_stored(path, hash, plan, method, scene_order) {
        Ok(reference) => Stored::Usable(Box::new(reference)),
        Err(stale) => stale,
    }
}

/// The reference stored at `path`, or why it cannot serve (`Stored::Stale`).
fn read_stored(
    path: &Path,
    hash: &str,
    plan: &Plan,
    method: Method,
    scene_order: Option<usize>,
) -> Result<Reference, Stored> {
    let bad = |why: String| Stored::Stale(format!("{}: {why}", path.display()));
    let text = read_text(path, MAX_STORED_BYTES, "stored reference")
        .map_err(|e| Stored::Stale(e.to_string()))?;
    let file: StoredFile =
        serde_saphyr::from_str(&text).map_err(|e| bad(format!("unreadable ({e})")))?;
    fits(&file, hash, plan, method, scene_order).map_err(bad)?;
    let csv = read_text(&history_path(path), MAX_HISTORY_BYTES, "stored history")
        .map_err(|e| Stored::Stale(e.to_string()))?;
    let history = stored_history(&file, &csv).map_err(bad)?;
    let means = file.means.map(StoredMeans::read).transpose().map_err(bad)?;
    // Means made on a mesh coarser than the grid now reaches cannot score its finest runs,
    // and what they resolve does not say so; the headlines' reference still serves, and the
    // diagram in the means waits for `--reference-means`. (An rtol tried as tight as the
    // means' own is covered: what they resolve includes a tenfold cut of it.)
    let (means_elements, means_order) = plan.means_mesh();
    let means = means.filter(|m| {
        m.elements >= means_elements && m.order.or(scene_order) >= means_order.or(scene_order)
    });
    Ok(Reference {
        method,
        rtol: file.rtol,
        elements: file.elements,
        order: file.order,
        settled_to: file.settled_to,
        mesh_gap: file.mesh_gap,
        headlines: file.headlines,
        history,
        wall_s: file.wall_s,
        made_by: file.made_by,
        means,
    })
}

/// Whether a stored reference was made from this scene, with this method, and tighter and
/// finer than everything the plan tries.
fn fits(
    file: &StoredFile,
    hash: &str,
    plan: &Plan,
    method: Method,
    scene_order: Option<usize>,
) -> Result<(), String> {
    if file.scene_hash != hash {
        return Err(format!(
            "made from another version of the scene ({}, the scene is now {hash})",
            file.scene_hash
        ));
    }
    let measure = |x: f64| x.is_finite() && x >= 0.0;
    if !measure(file.settled_to) || !file.mesh_gap.is_none_or(measure) {
        return Err("its settling or mesh gap is not a finite, non-negative number".into());
    }
    if !(measure(file.rtol) && file.rtol > 0.0) || !measure(file.wall_s) {
        return Err("its rtol or wall time is not a finite, positive number".into());
    }
    // A headline that is not a number would drop out of every score taken against it.
    if let Some(h) = file.headlines.iter().find(|h| !h.value.is_finite()) {
        return Err(format!(
            "its headline {} is {}, not a finite number",
            h.name, h.value
        ));
    }
    if file.method != method.name() {
        return Err(format!("made with {}, not {}", file.method, method.name()));
    }
    let start = plan.reference_rtol();
    if file.rtol > start * (1.0 + 1e-9) {
        return Err(format!(
            "made at rtol {:e}, not at or below {start:e}, a decade below the tightest tried",
            file.rtol
        ));
    }
    if let Some(finest) = plan.meshes.iter().copied().max() {
        if file.elements.is_none_or(|n| n < 2 * finest) {
            return Err(format!(
                "made on {:?} elements, not twice the finest tried, {finest}",
                file.elements
            ));
        }
    }
    match (plan.reference_order(), file.order.or(scene_order)) {
        (Some(highest), Some(made)) if made < highest => Err(format!(
            "made with elements of degree {made}, below the highest tried, {highest}"
        )),
        (Some(highest), None) => Err(format!(
            "made without a beam, and degree {highest} is tried"
        )),
        _ => Ok(()),
    }
}

/// The stored history's rows (t, values), checked against the hash stored with it; every
/// row finite and as wide as the reference says, the first at the run's start.
fn stored_history(file: &StoredFile, csv: &str) -> Result<Vec<(f64, Vec<f64>)>, String> {
    match &file.history_hash {
        Some(h) if *h == content_hash(csv) => {}
        Some(_) => {
            return Err(
                "its history file is not the one stored with it (its hash differs: cut or edited)"
                    .into(),
            )
        }
        None => {
            return Err("it holds no hash of its history, so the history cannot be checked".into())
        }
    }
    let mut history = Vec::new();
    for line in csv.lines() {
        let numbers: Result<Vec<f64>, _> = line.split(',').map(str::parse::<f64>).collect();
        match numbers {
            Ok(n) if n.len() == file.history_columns + 1 && n.iter().all(|x| x.is_finite()) => {
                history.push((n[0], n[1..].to_vec()));
            }
            _ => return Err(format!("its history has a malformed row: {line:.80}")),
        }
    }
    // Every run records its start, and the extremes a run is scored on include it (a sudden
    // load's highest point is the rest it starts from); a reference without that row scores
    // every run by what happens at t = 0.
    match history.first() {
        Some((t, _)) if *t == 0.0 => Ok(history),
        Some((t, _)) => Err(format!(
            "its history starts at t = {t}, not at the run's start, t = 0 (made by an older rollbeam that left the start row out)"
        )),
        None => Err("its history is empty".into()),
    }
}

/// The windowed means' reference stored at `path` for the scene text hashed `hash`, if there
/// is one: it outlives a recomputed reference of the headlines, which does not touch it.
pub fn stored_means(path: &Path, hash: &str) -> Option<MeansReference> {
    let text = read_text(path, MAX_STORED_BYTES, "stored reference").ok()?;
    let file: StoredFile = serde_saphyr::from_str(&text).ok()?;
    (file.scene_hash == hash)
        .then_some(file.means)
        .flatten()
        .and_then(|m| m.read().ok())
}

/// Put `means` into the reference stored at `path`, made from the scene text hashed `hash`.
pub fn store_means(means: &MeansReference, hash: &str, path: &Path) -> Result<(), Error> {
    let missing = || {
        Error::Input(format!(
            "{} holds no reference of this scene to add windowed means to; make it first with `rollbeam tradeoff SCENE --reference`",
            path.display()
        ))
    };
    let text = read_text(path, MAX_STORED_BYTES, "stored reference").map_err(|_| missing())?;
    let mut file: StoredFile = serde_saphyr::from_str(&text).map_err(|_| missing())?;
    if file.scene_hash != hash {
        return Err(missing());
    }
    file.means = Some(StoredMeans::from(means));
    write(path, &yaml(&file)?)
}
