// placeholder: filled by the quality_levels work
