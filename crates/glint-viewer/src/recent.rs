//! Recently opened scene files, kept in the user's configuration folder.

use std::path::{Path, PathBuf};

use glint_io::atomic::write_file_atomically;

const MAX_RECENT: usize = 8;

#[derive(Clone, Debug, Default)]
pub struct Recent {
    pub files: Vec<PathBuf>,
    store: Option<PathBuf>,
}

fn store_path() -> Option<PathBuf> {
    let base = std::env::var_os("XDG_CONFIG_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".config")))?;
    Some(base.join("glint").join("recent-scenes.txt"))
}

impl Recent {
    /// The list from the configuration folder (empty if there is none or it is unreadable).
    pub fn load() -> Self {
        let store = store_path();
        let files = store
            .as_deref()
            .and_then(|p| std::fs::read_to_string(p).ok())
            .map(|t| t.lines().filter(|l| !l.trim().is_empty()).map(PathBuf::from).collect())
            .unwrap_or_default();
        Self { files, store }
    }

    /// A list that is never written (tests).
    pub fn in_memory() -> Self {
        Self::default()
    }

    pub fn add(&mut self, path: &Path) {
        let path = path.canonicalize().unwrap_or_else(|_| path.to_owned());
        self.files.retain(|p| *p != path);
        self.files.insert(0, path);
        self.files.truncate(MAX_RECENT);
        if let Some(store) = &self.store {
            let text: String = self.files.iter().map(|p| format!("{}\n", p.display())).collect();
            let written = store
                .parent()
                .map_or(Ok(()), std::fs::create_dir_all)
                .and_then(|()| write_file_atomically(store, text.as_bytes()).map_err(|e| e.error));
            // Losing the list of recent files is not worth interrupting the user for.
            if let Err(e) = written {
                log::warn!("cannot save the recent scenes to {}: {e}", store.display());
            }
        }
    }
}
