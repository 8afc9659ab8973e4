//! Data channels for physicists, written beside the colour in EXR files: per pixel, what the
//! camera ray through the pixel's centre found (one ray, not an average over samples, so each
//! value belongs to one geodesic, as in Gyoto's and kerrz's images).
//!
//! | channel       | value                                                                        |
//! |---------------|------------------------------------------------------------------------------|
//! | `redshift`    | `g = ν_camera / ν_emitted` of the first thing the ray met: a surface or emitter (its local static observer; an accretion disk's gas in its own frame), or the sky (a static observer at infinity); NaN where the ray was captured or failed |
//! | `fate`        | what the ray met first: 0 a surface, 1 an emitter, 2 the sky, 3 the sky of a wormhole's other side, 4 captured, 5 failed |
//! | `disk_radius` | the Boyer–Lindquist radius where the ray met an accretion disk (in scene units), NaN elsewhere |
//!
//! and, with [`SpectrumChannels`], the spectrum the ray brings the camera, one channel per
//! wavelength.

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

impl FirstMet {
    /// Every fate, in the order of their values.
    pub const ALL: [FirstMet; 6] =
        [FirstMet::Surface, FirstMet::Emitter, FirstMet::Sky, FirstMet::OtherSky, FirstMet::Captured, FirstMet::Failed];

    /// The fate's name in summaries and statistics.
    pub fn name(self) -> &'static str {
        match self {
            FirstMet::Surface => "surface",
            FirstMet::Emitter => "emitter",
            FirstMet::Sky => "sky",
            FirstMet::OtherSky => "other_sky",
            FirstMet::Captured => "captured",
            FirstMet::Failed => "failed",
        }
    }
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
    /// The wavelengths of the spectral channels (none without [`SpectrumChannels`]).
    pub wavelengths: Vec<f64>,
    /// Pixel `i`'s spectral radiance at wavelength `k` is `spectra[i · wavelengths.len() + k]`.
    pub spectra: Vec<f32>,
}

impl DataLayer {
    /// The values of `channel`, row-major.
    pub fn samples(&self, channel: DataChannel) -> Vec<f32> {
        self.pixels.iter().map(|p| p.value(channel)).collect()
    }

    /// Memory a pixel's data takes from tracing to writing, with `channels` data channels and
    /// `wavelengths` spectral ones: its record, its spectrum (twice while the pixels' spectra are
    /// joined) and each channel's copy for the encoder.
    pub fn bytes_per_pixel(channels: usize, wavelengths: usize) -> u64 {
        (std::mem::size_of::<PixelData>() + 4 * channels + 12 * wavelengths) as u64
    }

    /// How many pixels' rays met each fate, indexed by [`FirstMet`]'s value.
    pub fn fate_counts(&self) -> [u64; FirstMet::ALL.len()] {
        let mut counts = [0; FirstMet::ALL.len()];
        for pixel in &self.pixels {
            counts[pixel.fate as usize] += 1;
        }
        counts
    }

    /// Every channel by its name, the data channels and then the spectral ones (see
    /// [`SpectrumChannels::name`]), each row-major: what an EXR image holds beside the colour.
    pub fn named_channels(&self) -> impl Iterator<Item = (String, Vec<f32>)> + '_ {
        let data = self.channels.iter().map(|&channel| (channel.name().to_owned(), self.samples(channel)));
        let spectra = (self.wavelengths.iter().enumerate())
            .map(|(k, &lambda)| (SpectrumChannels::name(lambda), self.spectral_samples(k)));
        data.chain(spectra)
    }

    /// Every pixel's spectral radiance at the `k`-th wavelength.
    pub fn spectral_samples(&self, k: usize) -> Vec<f32> {
        self.spectra.iter().skip(k).step_by(self.wavelengths.len().max(1)).copied().collect()
    }
}

/// Spectral radiance channels: at `count` wavelengths evenly spaced from `min` to `max` nm, the
/// spectral radiance per nm that the camera ray through each pixel's centre brings from what it
/// meets first, as the camera sees it (every frequency shift in, as the `[render]` toggles show
/// them): an emitter's light or the sky's; 0 from a surface that only reflects; NaN where the ray
/// was captured or failed. The units are the renderer's: an RGB colour's spectrum under D65 and a
/// blackbody's are normalised so that `∫ ȳ L_λ dλ / ∫ ȳ dλ` is their luminance. Channels are
/// named `S0.λnm`, λ with six decimals after a comma, after the spectral OpenEXR layout of
/// Fichet, Pacanowski & Wilkie (2021).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpectrumChannels {
    min: f64,
    max: f64,
    count: u32,
}

impl SpectrumChannels {
    /// The most channels one image takes.
    pub const MAX_COUNT: u32 = 4096;

    /// `count` wavelengths from `min` to `max` nm (`min` alone when `count` is 1); the message
    /// says what is wrong.
    pub fn new(min: f64, max: f64, count: u32) -> Result<Self, String> {
        if !(min.is_finite() && max.is_finite() && min > 0.0 && min <= max) {
            return Err(format!("the wavelengths must satisfy 0 < min ≤ max (nm), got {min} and {max}"));
        }
        if !(1..=Self::MAX_COUNT).contains(&count) || (count == 1 && min != max) {
            return Err(format!("count must be 1–{} (1 only with min = max), got {count}", Self::MAX_COUNT));
        }
        Ok(Self { min, max, count })
    }

    /// The wavelengths in nm, ascending.
    pub fn wavelengths(&self) -> Vec<f64> {
        let step = if self.count > 1 { (self.max - self.min) / f64::from(self.count - 1) } else { 0.0 };
        (0..self.count).map(|k| self.min + step * f64::from(k)).collect()
    }

    /// The channel name of wavelength `lambda` nm.
    pub fn name(lambda: f64) -> String {
        format!("S0.{}nm", format!("{lambda:.6}").replace('.', ","))
    }
}
