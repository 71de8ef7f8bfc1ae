//! A disk on a rigid curve's `history.csv`: one row per output time, columns as SCENE-FORMAT
//! names them.

use crate::run::RollingRun;

pub const COLUMNS: [&str; 18] = [
    "t",
    "disk.s",
    "disk.x",
    "disk.y",
    "disk.vx",
    "disk.vy",
    "disk.omega",
    "disk.rt",
    "disk.rn",
    "disk.phi",
    "disk.mu_needed",
    "disk.gap",
    "energy.kinetic",
    "energy.strain",
    "energy.potential",
    "energy.work",
    "energy.impact",
    "energy.total",
];

pub fn csv(r: &RollingRun) -> String {
    let mut out = COLUMNS.join(",");
    out.push('\n');
    for row in &r.rows {
        let d = &row.disk;
        // A rigid track stores no strain energy and carries no prescribed loads.
        let values = [
            row.t,
            d.s,
            d.x,
            d.y,
            d.vx,
            d.vy,
            d.omega,
            d.rt,
            d.rn,
            d.phi,
            d.mu_needed().unwrap_or(f64::NAN),
            row.gap,
            d.kinetic,
            0.0,
            d.potential,
            0.0,
            row.impact,
            row.energy(),
        ];
        super::push_row(&mut out, &values);
    }
    out
}
