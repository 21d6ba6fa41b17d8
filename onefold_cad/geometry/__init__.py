"""The pure geometry core (numpy and scipy only; never build123d or ezdxf)."""
