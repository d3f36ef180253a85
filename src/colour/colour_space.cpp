// placeholder: filled by the colour_space work
