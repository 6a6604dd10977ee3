//! (room reserved; filled by its issue)
