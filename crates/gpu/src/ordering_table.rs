//! Ordering tables: the DMA6 clear and DMA2 linked-list walk (gpu.md §2).
