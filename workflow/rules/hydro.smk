# Stage 'hydro': rules are added when the stage lands (see the issue tracker).
