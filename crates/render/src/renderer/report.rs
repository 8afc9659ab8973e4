//! A render's statistics as the JSON object that `nullpath render --stats` writes, the image's
//! metadata records and the Python module returns: one wording of them for every reader.

use super::{Outcome, RenderStats};
use crate::settings::RenderSettings;

impl RenderStats {
    /// The statistics of a render with `settings`, as JSON: rays, samples, seconds, NaN samples,
    /// ray fates, the image's size and samples per pixel asked for and reached, the estimated
    /// relative error, the outcome, and whether it is complete.
    pub fn to_json(&self, settings: &RenderSettings) -> serde_json::Value {
        let f = &self.paths.fates;
        serde_json::json!({
            "rays": self.paths.rays,
            "samples": self.samples,
            "seconds": self.seconds,
            "nan_samples": self.nan_samples,
            "fates": {
                "escaped": f.escaped, "captured": f.captured, "absorbed": f.absorbed,
                "traversed": f.traversed, "failed": f.failed,
            },
            "width": settings.width,
            "height": settings.height,
            "spp": settings.spp,
            "spp_min": self.spp_min,
            "spp_max": self.spp_max,
            "relative_error": self.relative_error,
            "outcome": match self.outcome {
                Outcome::Finished => "finished",
                Outcome::Converged => "converged",
                Outcome::Interrupted => "interrupted",
            },
            "complete": self.is_complete(),
        })
    }
}
