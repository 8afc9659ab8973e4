//! The files a scene names, read in one place: Wavefront OBJ meshes, images (textures and
//! environment maps), glTF files with the buffers and images they name, and volume grids.
//!
//! Every one of them is read under a [`ReadPolicy`] (see [`policy`]), because whoever wrote the
//! scene may not be whoever renders it, and each reader turns what it read into the renderer's
//! in-memory types ([`render::shape::TriangleMesh`], [`render::texture::image_data::ImageData`]),
//! so that the render crate reads no file a scene names. (The renderer still writes its own
//! outputs, images and checkpoints: that is the film's job, not this layer's.)
//!
//! Errors name the file as the scene wrote it and say why; none holds anything a file outside
//! the policy holds.
//!
//! | module                 | reads                                                                      |
//! |------------------------|----------------------------------------------------------------------------|
//! | [`policy`]             | which files may be read, and reading them: regular files of bounded size   |
//! | [`obj`]                | Wavefront OBJ meshes, into triangles with their placement baked in         |
//! | [`image`]              | PNG, JPEG, OpenEXR and Radiance HDR images, into linear RGB                |
//! | `gltf_import`          | glTF 2.0 files with their buffers and images: meshes, materials, lights…   |
//! | [`volume`]             | density and temperature grids of media: NumPy `.npy` and raw `f32` volumes |

pub(crate) mod gltf_import;
pub mod image;
pub mod obj;
pub mod policy;
pub mod volume;

pub use self::image::{load_image, load_image_path, ImageLoadError, ImageLoadErrorKind};
pub use obj::{load_obj, MeshError};
pub use policy::{ReadError, ReadPolicy, Resource, MAX_FILE_BYTES};
