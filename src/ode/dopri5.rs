//! Dormand–Prince 5(4): explicit, FSAL, fifth-order solution with a fourth-order error estimate
//! and Hairer's fourth-order continuous extension for dense output.

use super::{Attempt, Ctx, Dynamics, SolveError, Stepper};

const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Fifth-order weights minus fourth-order weights.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Dense-output weights of the continuous extension.
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

pub struct Dopri5 {
    k: [Vec<f64>; 7],
    y_old: Vec<f64>,
    y_new: Vec<f64>,
    /// Coefficients of the dense-output polynomial of the last accepted step.
    cont: [Vec<f64>; 5],
    t_old: f64,
    h: f64,
    /// Stage data of the pending attempt, kept until accept().
    t_try: f64,
    h_try: f64,
    stage: Vec<f64>,
}

impl Dopri5 {
    pub fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        Dopri5 {
            k: [z(), z(), z(), z(), z(), z(), z()],
            y_old: z(),
            y_new: z(),
            cont: [z(), z(), z(), z(), z()],
            t_old: 0.0,
            h: 0.0,
            t_try: 0.0,
            h_try: 0.0,
            stage: z(),
        }
    }
}

impl Stepper for Dopri5 {
    fn error_order(&self) -> u32 {
        4
    }

    fn start(
        &mut self,
        p: &dyn Dynamics,
        t0: f64,
        y0: &[f64],
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        self.y_old.copy_from_slice(y0);
        ctx.derivative(p, t0, y0, &mut self.k[0])
    }

    fn attempt(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<Attempt, SolveError> {
        let n = y.len();
        for s in 1..7 {
            for i in 0..n {
                let mut acc = 0.0;
                for (j, a) in A[s].iter().enumerate().take(s) {
                    acc += a * self.k[j][i];
                }
                self.stage[i] = y[i] + h * acc;
            }
            ctx.derivative(p, t + C[s] * h, &self.stage, &mut self.k[s])?;
        }
        // Stage 7 was evaluated at the fifth-order solution (the A[6] row are its weights).
        self.y_new.copy_from_slice(&self.stage);
        let err: Vec<f64> = (0..n)
            .map(|i| h * (0..7).map(|j| E[j] * self.k[j][i]).sum::<f64>())
            .collect();
        self.t_try = t;
        self.h_try = h;
        Ok(Attempt::Done {
            err: ctx.norm(&err, y, &self.y_new),
        })
    }

    fn y_new(&self) -> &[f64] {
        &self.y_new
    }

    fn accept(&mut self, _t_new: f64) {
        let h = self.h_try;
        for i in 0..self.y_new.len() {
            let ydiff = self.y_new[i] - self.y_old[i];
            let bspl = h * self.k[0][i] - ydiff;
            self.cont[0][i] = self.y_old[i];
            self.cont[1][i] = ydiff;
            self.cont[2][i] = bspl;
            self.cont[3][i] = ydiff - h * self.k[6][i] - bspl;
            self.cont[4][i] = h * (0..7).map(|j| D[j] * self.k[j][i]).sum::<f64>();
        }
        self.t_old = self.t_try;
        self.h = h;
        self.y_old.copy_from_slice(&self.y_new);
        // First same as last: the last stage is y' at the new point.
        let last = self.k[6].clone();
        self.k[0].copy_from_slice(&last);
    }

    fn interpolate(&self, t: f64, out: &mut [f64]) {
        let th = (t - self.t_old) / self.h;
        let th1 = 1.0 - th;
        for (i, o) in out.iter_mut().enumerate() {
            let c = |k: usize| self.cont[k][i];
            *o = c(0) + th * (c(1) + th1 * (c(2) + th * (c(3) + th1 * c(4))));
        }
    }

    fn interpolate_rate(&self, t: f64, out: &mut [f64]) {
        let th = (t - self.t_old) / self.h;
        let th1 = 1.0 - th;
        for (i, o) in out.iter_mut().enumerate() {
            let c = |k: usize| self.cont[k][i];
            // The polynomial's nested factors and their derivatives in θ, innermost first.
            let inner = c(3) + th1 * c(4);
            let b = c(2) + th * inner;
            let db = inner - th * c(4);
            let a = c(1) + th1 * b;
            let da = -b + th1 * db;
            *o = (a + th * da) / self.h;
        }
    }
}
