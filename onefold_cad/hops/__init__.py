"""``onefold hops``: a Grasshopper Hops server (ghhops-server on the standard
library's ``http.server``) with the components ``onefold/solve`` and
``onefold/fit``.

A Hops component in Grasshopper whose Path is
``http://127.0.0.1:5000/onefold/solve`` reads the component's inputs and
outputs from the server (``GET``), then sends its inputs as Hops' JSON
(``values``: one ``{"ParamName", "InnerTree"}`` per input) and draws the
answer. The inputs are the design flags of ``onefold solve``
(:mod:`.inputs`); a design is made, solved and reported exactly as the
command does (:mod:`.components`); a value the command refuses comes back
as a Hops error carrying the command's one-line message (:mod:`.server`).
The command's entry (:mod:`.launch`) checks that the ``rhino`` extra is
installed, listens and serves until Ctrl-C; :mod:`.guard` checks each
request's Host and Origin, :mod:`.http` bounds the HTTP server and
:mod:`.ghhops` imports ghhops-server with its logging kept to itself.
ghhops-server and rhino3dm come with the ``rhino`` extra.
"""
