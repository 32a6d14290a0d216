"""Developer tools of Road Sign Inventory (never shipped in the plugin zip)."""
