//! tradeoff.csv, tradeoff.txt and the work–precision diagrams.

use super::*;

/// tradeoff.csv and tradeoff.svg in `dir`; the closing lines for the terminal.
pub fn write_tradeoff(
    scene: &Scene,
    reference: &Reference,
    trials: &[Trial],
    dir: &Path,
) -> Result<Vec<String>, Error> {
    std::fs::create_dir_all(dir).map_err(|e| io_error(dir, e))?;
    let mut csv = String::from(
        "method,rtol,elements,order,model,status,headline_error,history_error,wall_s,steps,rejected,rhs_evals,mean_error\n",
    );
    for t in trials {
        let p = &t.point;
        let mesh = p.elements.map_or(String::new(), |n| n.to_string());
        let order = p.order.map_or(String::new(), |k| k.to_string());
        let model = p.model.map_or(String::new(), model_label);
        let _ = match &t.outcome {
            Ok(m) => writeln!(
                csv,
                "{},{:e},{mesh},{order},{model},ok,{:e},{:e},{},{},{},{},{}",
                p.method.name(),
                p.rtol,
                m.headline_error,
                m.history_error,
                m.wall_s,
                m.steps,
                m.rejected,
                m.rhs_evals,
                m.mean_error.map_or(String::new(), |e| format!("{e:e}"))
            ),
            Err(e) => writeln!(
                csv,
                "{},{:e},{mesh},{order},{model},\"failed: {}\",,,{},,,,",
                p.method.name(),
                p.rtol,
                e.replace('"', "'"),
                t.spent_s
            ),
        };
    }
    write(&dir.join("tradeoff.csv"), &csv)?;
    diagram(scene, trials, Score::Headlines, &dir.join("tradeoff.svg"))?;
    let mesh = match (reference.elements, reference.mesh_gap) {
        (None, _) => String::new(),
        (Some(_), Some(gap)) => format!(", and lie {gap:.1e} from a mesh twice as fine"),
        (Some(_), None) => {
            "; its mesh was not checked against a finer one (stored before rollbeam did so; --reference does)".to_string()
        }
    };
    let mut lines = vec![format!(
        "reference: {}, rtol {:.0e}{}{} ({:.2} s): headlines settled to {:.1e} at the last tenfold cut of rtol{mesh}",
        reference.method.name(),
        reference.rtol,
        reference
            .elements
            .map_or(String::new(), |n| format!(", {n} elements")),
        reference
            .order
            .map_or(String::new(), |k| format!(", degree {k}")),
        reference.wall_s,
        reference.settled_to,
    )];
    lines.extend(cheapest_lines(
        trials,
        Score::Headlines,
        reference.resolves(),
        "",
    ));
    if let Some(means) = &reference.means {
        lines.push(format!(
            "windowed means' reference: {}, rtol {:.0e}{}{} ({:.2} s): resolves {:.1e} (a tenfold cut of rtol, and a mesh half as fine)",
            means.method.name(),
            means.rtol,
            means
                .elements
                .map_or(String::new(), |n| format!(", {n} elements")),
            means
                .order
                .map_or(String::new(), |k| format!(", degree {k}")),
            means.wall_s,
            means.resolves,
        ));
        lines.extend(cheapest_lines(
            trials,
            Score::Means,
            means.resolves,
            "in the windowed means ",
        ));
        diagram(scene, trials, Score::Means, &dir.join("tradeoff-means.svg"))?;
    } else {
        // A means diagram from an earlier run would otherwise pass for this one's.
        let _ = std::fs::remove_file(dir.join("tradeoff-means.svg"));
    }
    let mut summary = String::new();
    for l in &lines {
        let _ = writeln!(summary, "{l}");
    }
    write(&dir.join("tradeoff.txt"), &summary)?;
    Ok(lines)
}

/// The cheapest setting for each of [`TARGETS`] in `score`, a line each.
pub(super) fn cheapest_lines(
    trials: &[Trial],
    score: Score,
    resolves: f64,
    what: &str,
) -> Vec<String> {
    TARGETS
        .iter()
        .map(|&target| match cheapest_in(trials, target, score) {
            _ if target < resolves => {
                format!("{what}{target:.0e}: below what the reference resolves ({resolves:.1e})")
            }
            Some(t) => {
                let m = t.outcome.as_ref().expect("cheapest is a finished run");
                format!(
                    "{what}{target:.0e}: {} — error {:.1e}, {:.2e} s, {} steps",
                    t.settings(),
                    score.of(m).expect("cheapest has the score"),
                    m.wall_s,
                    m.steps
                )
            }
            None => format!("{what}{target:.0e}: no setting tried reaches it"),
        })
        .collect()
}

/// Error in `score` against the work, log–log, a line per method, mesh, degree and model. The
/// work is the right-hand sides evaluated, which a rerun repeats exactly, so the committed
/// diagrams change only where the physics or the method does; `tradeoff.csv` and
/// `tradeoff.txt` keep the wall times.
pub(super) fn diagram(
    scene: &Scene,
    trials: &[Trial],
    score: Score,
    path: &Path,
) -> Result<(), Error> {
    let err =
        |e: &dyn std::fmt::Display| Error::Output(format!("cannot draw {}: {e}", path.display()));
    let (mut lines, by_method) = lines_of(trials, score);
    let Some((x0, x1, y0, y1)) = bounds(lines.iter().flat_map(|(_, p)| p.iter())) else {
        return Ok(());
    };
    // More lines than the palette has colours cannot be told apart (D44's grid makes 37):
    // then each method is drawn as its front, the cheapest of its settings for each accuracy,
    // over every setting tried in grey; tradeoff.csv names the settings.
    let everything: Vec<(f64, f64)> = lines.iter().flat_map(|(_, p)| p.clone()).collect();
    let fronts = lines.len() > PALETTE.len();
    if fronts {
        lines = by_method
            .into_iter()
            .map(|(method, pts)| {
                (
                    format!("{method}: the cheapest for each accuracy"),
                    front(pts),
                )
            })
            .collect();
    }
    crate::output::plots::svg(path, (900, 600), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                match score {
                    Score::Headlines => format!("{}: work–precision", scene.name),
                    Score::Means => format!("{}: work–precision in the windowed means", scene.name),
                },
                ("sans-serif", 22),
            )
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(
                (x0 / 1.5..x1 * 1.5).log_scale(),
                // From just below a whole decade: plotters labels a log axis from the first
                // decade inside its range upwards, so errors below that would go unlabelled.
                (0.99 * 10f64.powf((y0 / 3.0).log10().floor())..y1 * 3.0).log_scale(),
            )
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("right-hand sides evaluated (work)")
            .y_desc(match score {
                Score::Headlines => "headline error (relative)",
                Score::Means => "error in the windowed means (relative)",
            })
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(|e| err(&e))?;
        if fronts {
            chart
                .draw_series(
                    everything
                        .iter()
                        .map(|&p| Circle::new(p, 2, RGBColor(150, 150, 150).filled())),
                )
                .map_err(|e| err(&e))?
                .label("every setting tried")
                .legend(|(x, y)| Circle::new((x + 10, y), 2, RGBColor(150, 150, 150).filled()));
        }
        for (i, (name, pts)) in lines.iter().enumerate() {
            let color = PALETTE[i % PALETTE.len()];
            let style = color.stroke_width(2);
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), style))
                .map_err(|e| err(&e))?
                .label(name.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
                .map_err(|e| err(&e))?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| err(&e))?;
        Ok(())
    })
}

/// The smallest and largest work and error of the points, `None` without points.
fn bounds<'p>(points: impl Iterator<Item = &'p (f64, f64)>) -> Option<(f64, f64, f64, f64)> {
    let (x0, x1, y0, y1) = points.fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    x0.is_finite().then_some((x0, x1, y0, y1))
}

/// Points (work, error): one line per setting (method, mesh, model), and all of a method's
/// settings together.
type Lines<S> = Vec<(S, Vec<(f64, f64)>)>;

/// Each scored trial's (work, error) on its setting's line and on its method's.
fn lines_of(trials: &[Trial], score: Score) -> (Lines<String>, Lines<&'static str>) {
    let mut lines: Lines<String> = Vec::new();
    let mut by_method: Lines<&'static str> = Vec::new();
    for t in trials {
        let Ok(m) = &t.outcome else { continue };
        let Some(error) = score.of(m) else { continue };
        let p = &t.point;
        let mut name = match (p.elements, p.order) {
            (Some(n), Some(k)) => format!("{} ({n} el. p{k})", p.method.name()),
            (Some(n), None) => format!("{} ({n} el.)", p.method.name()),
            (None, _) => p.method.name().to_string(),
        };
        if let Some(m) = p.model {
            name = format!("{name} {}", model_label(m));
        }
        let point = ((m.rhs_evals as f64).max(1.0), error.max(1e-12));
        match lines.iter_mut().find(|(n, _)| *n == name) {
            Some((_, pts)) => pts.push(point),
            None => lines.push((name, vec![point])),
        }
        match by_method.iter_mut().find(|(n, _)| *n == p.method.name()) {
            Some((_, pts)) => pts.push(point),
            None => by_method.push((p.method.name(), vec![point])),
        }
    }
    (lines, by_method)
}

/// The points no other point beats in both work and error, by increasing work.
fn front(mut points: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    points.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut best = f64::INFINITY;
    points.retain(|&(_, e)| {
        let better = e < best;
        best = best.min(e);
        better
    });
    points
}
