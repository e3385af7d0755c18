//! Dormand and Prince's explicit Runge-Kutta method of order 8 with error estimators
//! of orders 5 and 3 (P. J. Prince, J. R. Dormand, "High order embedded Runge-Kutta
//! formulae", J. Comp. Appl. Math. 7, 1981; the coefficients and the combined error
//! estimate of Hairer's code DOP853, Solving ODEs I, section II.10): twelve stages per
//! step and one more at the accepted end state.

// The coefficients as published, to 30 digits; the compiler rounds them to f64.
#![allow(clippy::excessive_precision)]

use super::{OdeError, Pair, Settings, Solution, integrate, zeros_like};
use nalgebra::{DefaultAllocator, Dim, OVector, allocator::Allocator};

/// Nodes c1..c12 (DOP853's C2..C11; c12 = 1: the twelfth stage is at the step end).
const C: [f64; 12] = [
    0.0,
    0.526001519587677318785587544488e-1,
    0.789002279381515978178381316732e-1,
    0.118350341907227396726757197510,
    0.281649658092772603273242802490,
    0.333333333333333333333333333333,
    0.25,
    0.307692307692307692307692307692,
    0.651282051282051282051282051282,
    0.6,
    0.857142857142857142857142857142,
    1.0,
];

/// Coupling coefficients a_ij of stages 2..12 (DOP853's A21..A1211).
const A: [&[f64]; 12] = [
    &[],
    &[5.26001519587677318785587544488e-2],
    &[
        1.97250569845378994544595329183e-2,
        5.91751709536136983633785987549e-2,
    ],
    &[
        2.95875854768068491816892993775e-2,
        0.0,
        8.87627564304205475450678981324e-2,
    ],
    &[
        2.41365134159266685502369798665e-1,
        0.0,
        -8.84549479328286085344864962717e-1,
        9.24834003261792003115737966543e-1,
    ],
    &[
        3.7037037037037037037037037037e-2,
        0.0,
        0.0,
        1.70828608729473871279604482173e-1,
        1.25467687566822425016691814123e-1,
    ],
    &[
        3.7109375e-2,
        0.0,
        0.0,
        1.70252211019544039314978060272e-1,
        6.02165389804559606850219397283e-2,
        -1.7578125e-2,
    ],
    &[
        3.70920001185047927108779319836e-2,
        0.0,
        0.0,
        1.70383925712239993810214054705e-1,
        1.07262030446373284651809199168e-1,
        -1.53194377486244017527936158236e-2,
        8.27378916381402288758473766002e-3,
    ],
    &[
        6.24110958716075717114429577812e-1,
        0.0,
        0.0,
        -3.36089262944694129406857109825,
        -8.68219346841726006818189891453e-1,
        2.75920996994467083049415600797e1,
        2.01540675504778934086186788979e1,
        -4.34898841810699588477366255144e1,
    ],
    &[
        4.77662536438264365890433908527e-1,
        0.0,
        0.0,
        -2.48811461997166764192642586468,
        -5.90290826836842996371446475743e-1,
        2.12300514481811942347288949897e1,
        1.52792336328824235832596922938e1,
        -3.32882109689848629194453265587e1,
        -2.03312017085086261358222928593e-2,
    ],
    &[
        -9.3714243008598732571704021658e-1,
        0.0,
        0.0,
        5.18637242884406370830023853209,
        1.09143734899672957818500254654,
        -8.14978701074692612513997267357,
        -1.85200656599969598641566180701e1,
        2.27394870993505042818970056734e1,
        2.49360555267965238987089396762,
        -3.0467644718982195003823669022,
    ],
    &[
        2.27331014751653820792359768449,
        0.0,
        0.0,
        -1.05344954667372501984066689879e1,
        -2.00087205822486249909675718444,
        -1.79589318631187989172765950534e1,
        2.79488845294199600508499808837e1,
        -2.85899827713502369474065508674,
        -8.87285693353062954433549289258,
        1.23605671757943030647266201528e1,
        6.43392746015763530355970484046e-1,
    ],
];

/// Eighth-order weights b1, b6..b12 (b2..b5 = 0).
const B1: f64 = 5.42937341165687622380535766363e-2;
const B6: f64 = 4.45031289275240888144113950566;
const B7: f64 = 1.89151789931450038304281599044;
const B8: f64 = -5.8012039600105847814672114227;
const B9: f64 = 3.1116436695781989440891606237e-1;
const B10: f64 = -1.52160949662516078556178806805e-1;
const B11: f64 = 2.01365400804030348374776537501e-1;
const B12: f64 = 4.47106157277725905176885569043e-2;

/// Weights of the third-order estimator on stages 1, 9 and 12 (DOP853's BHH1..3).
const BHH1: f64 = 0.244094488188976377952755905512;
const BHH2: f64 = 0.733846688281611857341361741547;
const BHH3: f64 = 0.220588235294117647058823529412e-1;

/// Fifth-order error weights on stages 1, 6..12 (DOP853's ER1, ER6..ER12).
const ER1: f64 = 0.1312004499419488073250102996e-1;
const ER6: f64 = -0.1225156446376204440720569753e1;
const ER7: f64 = -0.4957589496572501915214079952;
const ER8: f64 = 0.1664377182454986536961530415e1;
const ER9: f64 = -0.3503288487499736816886487290;
const ER10: f64 = 0.3341791187130174790297318841;
const ER11: f64 = 0.8192320648511571246570742613e-1;
const ER12: f64 = -0.2235530786388629525884427845e-1;

/// Integrates `y' = f(x, y)` from `(x0, y0)` to `x_end` with DOP853, landing on `x_end`.
/// `f` writes the derivative (NaN where it cannot be evaluated).
pub fn dop853<D, F>(
    f: F,
    x0: f64,
    x_end: f64,
    y0: OVector<f64, D>,
    settings: &Settings,
) -> Result<Solution<D>, OdeError>
where
    D: Dim,
    DefaultAllocator: Allocator<D>,
    F: FnMut(f64, &OVector<f64, D>, &mut OVector<f64, D>),
{
    integrate::<D, F, _, Dop853<D>>(f, x0, x_end, y0, settings, |_, _| {})
}

/// As [`dop853`], calling `observe(x, y)` at every accepted point (the integrator's own
/// steps, the end included; not the start).
pub fn dop853_observed<D, F, O>(
    f: F,
    x0: f64,
    x_end: f64,
    y0: OVector<f64, D>,
    settings: &Settings,
    observe: O,
) -> Result<Solution<D>, OdeError>
where
    D: Dim,
    DefaultAllocator: Allocator<D>,
    F: FnMut(f64, &OVector<f64, D>, &mut OVector<f64, D>),
    O: FnMut(f64, &OVector<f64, D>),
{
    integrate::<D, F, O, Dop853<D>>(f, x0, x_end, y0, settings, observe)
}

/// The stages of one step and its end state.
struct Dop853<D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    k: [OVector<f64, D>; 12],
    y_new: OVector<f64, D>,
}

impl<D: Dim> Pair<D> for Dop853<D>
where
    DefaultAllocator: Allocator<D>,
{
    const ORDER_INVERSE: f64 = 0.125;
    const STAGE_EVALUATIONS: u32 = 11;

    fn new(y: &OVector<f64, D>) -> Self {
        Self {
            k: std::array::from_fn(|_| zeros_like(y)),
            y_new: zeros_like(y),
        }
    }

    fn alpha(beta: f64) -> f64 {
        1.0 / 8.0 - beta * 0.2
    }

    fn start_derivative(&mut self) -> &mut OVector<f64, D> {
        &mut self.k[0]
    }

    fn attempt<F>(
        &mut self,
        f: &mut F,
        x: f64,
        y: &OVector<f64, D>,
        h: f64,
        settings: &Settings,
    ) -> f64
    where
        F: FnMut(f64, &OVector<f64, D>, &mut OVector<f64, D>),
    {
        let Self { k, y_new } = self;
        for stage in 1..12 {
            y_new.copy_from(y);
            for (j, &a) in A[stage].iter().enumerate() {
                let ha = h * a;
                for (yi, &kj) in y_new.iter_mut().zip(k[j].iter()) {
                    *yi += kj * ha;
                }
            }
            f(x + h * C[stage], y_new, &mut k[stage]);
        }
        let (mut err5, mut err3) = (0.0, 0.0);
        for i in 0..y.len() {
            let increment = k[0][i] * B1
                + k[5][i] * B6
                + k[6][i] * B7
                + k[7][i] * B8
                + k[8][i] * B9
                + k[9][i] * B10
                + k[10][i] * B11
                + k[11][i] * B12;
            y_new[i] = y[i] + increment * h;
            let scale = settings.atol + y[i].abs().max(y_new[i].abs()) * settings.rtol;
            let e5 = k[0][i] * ER1
                + k[5][i] * ER6
                + k[6][i] * ER7
                + k[7][i] * ER8
                + k[8][i] * ER9
                + k[9][i] * ER10
                + k[10][i] * ER11
                + k[11][i] * ER12;
            err5 += (e5 / scale) * (e5 / scale);
            let e3 = increment - k[0][i] * BHH1 - k[8][i] * BHH2 - k[11][i] * BHH3;
            err3 += (e3 / scale) * (e3 / scale);
        }
        // Hairer's combination of the two estimates (Solving ODEs I, (10.17)).
        let mut denominator = err5 + 0.01 * err3;
        if denominator <= 0.0 {
            denominator = 1.0;
        }
        h.abs() * err5 * (1.0 / (denominator * y.len() as f64)).sqrt()
    }

    fn accept<F>(&mut self, f: &mut F, x_end: f64, y: &mut OVector<f64, D>) -> u32
    where
        F: FnMut(f64, &OVector<f64, D>, &mut OVector<f64, D>),
    {
        std::mem::swap(y, &mut self.y_new);
        f(x_end, y, &mut self.k[0]);
        1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Truth: the simplifying and quadrature conditions of an eighth-order method
    /// (Hairer, Norsett, Wanner, Solving ODEs I, II.5 and II.10): each row of A sums to
    /// its node (so the twelfth stage, whose row sums to 1, lies at the step end), the
    /// weights b integrate c^(q-1) exactly for q = 1..8, the fifth-order error weights
    /// annihilate c^(q-1) for q = 1..5, and the third-order estimator b - bhh
    /// integrates c^(q-1) exactly for q = 1..3 (so b - bhh annihilates them).
    #[test]
    fn coefficients_meet_the_order_conditions() {
        for (i, row) in A.iter().enumerate().skip(1) {
            let sum: f64 = row.iter().sum();
            assert!((sum - C[i]).abs() < 1e-13, "row {} sums to {sum}", i + 1);
        }
        let mut b = [0.0; 12];
        let mut er = [0.0; 12];
        let mut bhh = [0.0; 12];
        for (i, (wb, we)) in [
            (B1, ER1),
            (B6, ER6),
            (B7, ER7),
            (B8, ER8),
            (B9, ER9),
            (B10, ER10),
            (B11, ER11),
            (B12, ER12),
        ]
        .into_iter()
        .enumerate()
        {
            let stage = if i == 0 { 0 } else { i + 4 };
            b[stage] = wb;
            er[stage] = we;
        }
        bhh[0] = BHH1;
        bhh[8] = BHH2;
        bhh[11] = BHH3;
        let moment =
            |w: &[f64; 12], q: i32| -> f64 { (0..12).map(|i| w[i] * C[i].powi(q - 1)).sum() };
        for q in 1..=8 {
            assert!(
                (moment(&b, q) - 1.0 / f64::from(q)).abs() < 1e-13,
                "b, q = {q}"
            );
        }
        for q in 1..=5 {
            assert!(
                moment(&er, q).abs() < 1e-13,
                "er, q = {q}: {}",
                moment(&er, q)
            );
        }
        for q in 1..=3 {
            let residual = moment(&b, q) - moment(&bhh, q);
            assert!(residual.abs() < 1e-13, "bhh, q = {q}: {residual}");
        }
    }
}
