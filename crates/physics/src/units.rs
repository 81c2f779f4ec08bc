//! The trade's units, in SI: rule books and bat makers state lengths in inches, weights in
//! ounces and swing weights in ounce-square-inches.

/// One mile per hour, m/s.
pub const MPH: f64 = 0.447_04;
/// One inch, m.
pub const INCH: f64 = 0.0254;
/// One ounce (avoirdupois), kg.
pub const OUNCE: f64 = 0.028349523125;
/// One ounce-square-inch, kg·m² (a swing weight's unit in the trade).
pub const OUNCE_SQUARE_INCH: f64 = OUNCE * INCH * INCH;
