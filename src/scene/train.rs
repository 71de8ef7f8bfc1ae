//! A train of axle loads: EN 1991-2's HSLM-A or the scene's own axles, as forces or masses.

use super::*;

/// Most axles a train may have: every one is a load the beam reads at every evaluation.
pub(super) const MAX_AXLES: usize = 10_000;

/// Most moving-mass axles on the deck at one time.
pub(super) const MAX_MASSES_ON_DECK: usize = 100;

/// The most of the increasing positions `x` that fit in one window of length `span`.
pub(super) fn most_within(x: &[f64], span: f64) -> usize {
    let mut first = 0;
    let mut most = 0;
    for (last, &xl) in x.iter().enumerate() {
        while xl - x[first] > span {
            first += 1;
        }
        most = most.max(last + 1 - first);
    }
    most
}

/// The train as the file gives it: an HSLM name, or axles and their load; its speed and model.
pub(super) fn train(
    c: &Checker,
    file: &Spanned<TrainFile>,
    beam: &BeamSpec,
    gravity: f64,
) -> Result<Train, Error> {
    let t = &file.value;
    let speed = c.positive(&t.speed, "train.speed")?;
    let speed = c.speed(t.speed.referenced.line(), "train.speed", speed)?;
    let model = train_model(c, t, gravity)?;
    let (name, axles, loads) =
        match (&t.hslm, &t.axles, &t.load) {
            (Some(h), None, None) => {
                let (axles, force) = hslm(&h.value).map_or_else(
                    || {
                        c.err(
                            h.referenced.line(),
                            "train.hslm",
                            format!(
                                "is {}; EN 1991-2's HSLM-A trains are {HSLM_NAMES}",
                                quote(&h.value)
                            ),
                        )
                    },
                    Ok,
                )?;
                let loads = vec![force; axles.len()];
                (h.value.clone(), axles, loads)
            }
            (Some(h), _, _) => return c.err(
                h.referenced.line(),
                "train.hslm",
                "names a train whose axles and loads are EN 1991-2's: leave `axles` and `load` out",
            ),
            (None, Some(a), Some(l)) => {
                let (axles, loads) = listed_axles(c, a, l, model)?;
                ("axles".to_string(), axles, loads)
            }
            (None, Some(_), None) => {
                return c.err(
                    file.referenced.line(),
                    "train.load",
                    "is missing: give the force per axle (N), or one per axle",
                )
            }
            (None, None, _) => {
                return c.err(
                    file.referenced.line(),
                    "train",
                    "needs `hslm` (A1 to A10), or `axles` and `load`",
                )
            }
        };
    if model == TrainModel::MovingMass {
        let span = (beam.to[0] - beam.from[0]).hypot(beam.to[1] - beam.from[1]);
        let most = most_within(&axles, span);
        if most > MAX_MASSES_ON_DECK {
            return c.err(
                file.referenced.line(),
                "train",
                format!("puts up to {most} moving-mass axles on the {span} m deck at once; at most {MAX_MASSES_ON_DECK} can be (each one's inertia couples to every other's through the beam, so the work grows with their square): use moving-force, or fewer axles"),
            );
        }
    }
    let masses = match model {
        TrainModel::MovingForce => Vec::new(),
        TrainModel::MovingMass => loads.iter().map(|p| p / gravity).collect(),
    };
    Ok(Train {
        name,
        axles,
        loads,
        speed,
        model,
        masses,
        patch: patch::dispersed_half_width(beam.depth),
    })
}

/// How a train's axles act: moving forces (the default) or moving masses, whose masses are
/// their loads over a positive gravity.
fn train_model(c: &Checker, t: &TrainFile, gravity: f64) -> Result<TrainModel, Error> {
    Ok(match &t.model {
        None => TrainModel::MovingForce,
        Some(m) if m.value == "moving-force" => TrainModel::MovingForce,
        Some(m) if m.value == "moving-mass" => {
            if !(gravity > 0.0) {
                return c.err(
                    m.referenced.line(),
                    "train.model",
                    format!("is moving-mass, whose axle masses are their loads over gravity, and gravity is {gravity}: give a positive `gravity`, or use moving-force"),
                );
            }
            TrainModel::MovingMass
        }
        Some(m) => {
            return c.err(
                m.referenced.line(),
                "train.model",
                format!(
                    "is {}; a train's axles are moving-force or moving-mass",
                    quote(&m.value)
                ),
            )
        }
    })
}

/// A train's own axles (distances behind the first, from 0 and increasing) and their loads
/// (one for all, or one each; positive for moving masses).
fn listed_axles(
    c: &Checker,
    a: &Spanned<Vec<f64>>,
    l: &Spanned<AxleLoads>,
    model: TrainModel,
) -> Result<(Vec<f64>, Vec<f64>), Error> {
    let line = a.referenced.line();
    let axles = a.value.clone();
    if axles.is_empty() || axles.len() > MAX_AXLES {
        return c.err(
            line,
            "train.axles",
            format!("must hold 1 to {MAX_AXLES} axles"),
        );
    }
    if axles.iter().any(|x| !x.is_finite() || *x < 0.0) || axles.windows(2).any(|w| w[1] <= w[0]) {
        return c.err(
            line,
            "train.axles",
            "must be distances behind the first axle (m), from 0 and increasing",
        );
    }
    let loads = match &l.value {
        AxleLoads::All(p) => vec![*p; axles.len()],
        AxleLoads::Each(each) if each.len() == axles.len() => each.clone(),
        AxleLoads::Each(each) => {
            return c.err(
                l.referenced.line(),
                "train.load",
                format!(
                    "lists {} loads for {} axles: give one per axle, or one number for all",
                    each.len(),
                    axles.len()
                ),
            )
        }
    };
    if loads.iter().any(|p| !p.is_finite()) {
        return c.err(
            l.referenced.line(),
            "train.load",
            "must hold finite forces (N)",
        );
    }
    if model == TrainModel::MovingMass && loads.iter().any(|p| !(*p > 0.0)) {
        return c.err(
                l.referenced.line(),
                "train.load",
                "must hold positive forces (N) with moving-mass, whose axle masses are the loads over gravity",
            );
    }
    Ok((axles, loads))
}
