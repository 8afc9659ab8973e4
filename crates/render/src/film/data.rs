//! Data channels for physicists, written beside the colour in EXR files: per pixel, what the
//! camera ray through the pixel's centre found (one ray, not an average over samples, so each
//! value belongs to one geodesic, as in Gyoto's and kerrz's images).
//!
//! | channel       | value                                                                        |
//! |---------------|------------------------------------------------------------------------------|
//! | `redshift`    | `g = ν_camera / ν_emitted` of the first thing the ray met: a surface or emitter (its local static observer; an accretion disk's gas in its own frame), or the sky (a static observer at infinity); NaN where the ray was captured or failed |
//! | `fate`        | what the ray met first: 0 a surface, 1 an emitter, 2 the sky, 3 the sky of a wormhole's other side, 4 captured, 5 failed |
//! | `disk_radius` | the Boyer–Lindquist radius where the ray met an accretion disk (in scene units), NaN elsewhere |

/// A data channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DataChannel {
    Redshift,
    Fate,
    DiskRadius,
}

impl DataChannel {
    /// Every channel, in the order scene files list them.
    pub const ALL: [DataChannel; 3] = [DataChannel::Redshift, DataChannel::Fate, DataChannel::DiskRadius];

    /// The channel's name in scene files and EXR files.
    pub fn name(self) -> &'static str {
        match self {
            DataChannel::Redshift => "redshift",
            DataChannel::Fate => "fate",
            DataChannel::DiskRadius => "disk_radius",
        }
    }
}

/// What a camera ray met first ([`DataChannel::Fate`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FirstMet {
    Surface = 0,
    Emitter = 1,
    Sky = 2,
    OtherSky = 3,
    Captured = 4,
    Failed = 5,
}

/// One pixel's data.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelData {
    pub redshift: f64,
    pub fate: FirstMet,
    pub disk_radius: f64,
}

impl PixelData {
    fn value(&self, channel: DataChannel) -> f32 {
        match channel {
            DataChannel::Redshift => self.redshift as f32,
            DataChannel::Fate => f32::from(self.fate as u8),
            DataChannel::DiskRadius => self.disk_radius as f32,
        }
    }
}

/// The data channels of an image, row-major like the film.
#[derive(Clone, Debug, PartialEq)]
pub struct DataLayer {
    pub width: u32,
    pub height: u32,
    pub channels: Vec<DataChannel>,
    pub pixels: Vec<PixelData>,
}

impl DataLayer {
    /// The values of `channel`, row-major.
    pub fn samples(&self, channel: DataChannel) -> Vec<f32> {
        self.pixels.iter().map(|p| p.value(channel)).collect()
    }
}
