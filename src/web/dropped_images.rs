//! Images dropped on the page's canvas, for the texture channels of a
//! multipass shader (docs/web.md, "Multipass shaders"). A Shadertoy JSON
//! names its textures by the site's paths (`/media/a/8de3….jpg`), which
//! the page cannot fetch: a texture reads the dropped image of the same
//! file name, else the newest dropped image no other texture took, else
//! the built-in noise, and the page says which.

use std::collections::VecDeque;
use std::path::{Path, PathBuf};

/// The page keeps this many images (a shader has at most 5 passes of 4
/// channels, and few read more than two images); dropping one more
/// forgets the oldest.
pub const MAX_IMAGES: usize = 8;

struct DroppedImage {
    /// Tells two drops of files with the same name apart (the GPU's copy
    /// of an image is kept by its key, [`DroppedImages::key`]).
    serial: u64,
    name: String,
    image: image::RgbaImage,
}

/// What a texture channel reads, by [`DroppedImages::assign`].
pub enum Assigned {
    /// The image dropped as `name`, known to the GPU side by `key`.
    Image { key: PathBuf, name: String },
    /// No image for it: the built-in noise.
    Missing,
}

#[derive(Default)]
pub struct DroppedImages {
    /// Oldest first.
    images: VecDeque<DroppedImage>,
    serial: u64,
}

impl DroppedImages {
    /// Keeps the image dropped as `name`, in place of one dropped earlier
    /// under the same name.
    pub fn add(&mut self, name: &str, image: image::RgbaImage) {
        self.images.retain(|i| i.name != name);
        if self.images.len() == MAX_IMAGES {
            self.images.pop_front();
        }
        self.serial += 1;
        self.images.push_back(DroppedImage {
            serial: self.serial,
            name: name.to_string(),
            image,
        });
    }

    /// The images for the texture sources `srcs` (distinct, in the order
    /// the passes read them): the one of the same file name, else the
    /// newest one that no source names nor took before.
    pub fn assign(&self, srcs: &[String]) -> Vec<Assigned> {
        let by_name = |src: &str| {
            let name = Path::new(src).file_name()?.to_str()?;
            self.images.iter().position(|i| i.name == name)
        };
        let mut taken: Vec<usize> = srcs.iter().filter_map(|s| by_name(s)).collect();
        srcs.iter()
            .map(|src| {
                let k = by_name(src).or_else(|| {
                    let free = (0..self.images.len()).rev().find(|k| !taken.contains(k))?;
                    taken.push(free);
                    Some(free)
                });
                match k {
                    Some(k) => Assigned::Image {
                        key: self.key(k),
                        name: self.images[k].name.clone(),
                    },
                    None => Assigned::Missing,
                }
            })
            .collect()
    }

    fn key(&self, k: usize) -> PathBuf {
        let image = &self.images[k];
        PathBuf::from(format!("dropped/{}/{}", image.serial, image.name))
    }

    /// The image of a key [`assign`](Self::assign) gave.
    pub fn load(&self, key: &Path) -> Result<image::RgbaImage, String> {
        (0..self.images.len())
            .find(|&k| self.key(k) == key)
            .map(|k| self.images[k].image.clone())
            .ok_or_else(|| format!("{}: no such image dropped on the page", key.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(images: &DroppedImages, srcs: &[&str]) -> Vec<String> {
        let srcs: Vec<String> = srcs.iter().map(|s| s.to_string()).collect();
        images
            .assign(&srcs)
            .into_iter()
            .map(|a| match a {
                Assigned::Image { name, .. } => name,
                Assigned::Missing => "-".into(),
            })
            .collect()
    }

    #[test]
    fn textures_take_their_namesake_then_the_newest_free_image() {
        let mut images = DroppedImages::default();
        assert_eq!(names(&images, &["/media/a/x.png"]), ["-"]);
        images.add("wood.png", image::RgbaImage::new(1, 1));
        images.add("x.png", image::RgbaImage::new(2, 2));
        images.add("rock.jpg", image::RgbaImage::new(3, 3));
        assert_eq!(
            names(
                &images,
                &["/media/a/1.jpg", "/media/a/x.png", "/b/2.png", "3.png"]
            ),
            ["rock.jpg", "x.png", "wood.png", "-"]
        );
        let key = match &images.assign(&["x.png".into()])[0] {
            Assigned::Image { key, .. } => key.clone(),
            Assigned::Missing => panic!("x.png was dropped"),
        };
        assert_eq!(images.load(&key).unwrap().width(), 2);
        // The same name again replaces it, under a new key.
        images.add("x.png", image::RgbaImage::new(4, 4));
        assert!(images.load(&key).is_err());
        for k in 0..MAX_IMAGES {
            images.add(&format!("{k}.png"), image::RgbaImage::new(1, 1));
        }
        assert_eq!(images.images.len(), MAX_IMAGES);
        assert_eq!(names(&images, &["wood.png"]), ["7.png"], "the oldest went");
    }
}
