//! GP0/GP1 command-stream text format (docs/formats.md).
